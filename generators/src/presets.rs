//! Each search method's settings for one generator, where a scene leaves them out.

use shapegen_runtime::optimize::{GaSettings, McmcSettings, Order, SmcSettings};

/// Each search method's settings for one generator, taken where a scene's `[optimizer]`
/// table leaves a field out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Presets {
    /// The genetic algorithm's (and the multi-objective GA's breeding).
    pub ga: GaSettings,
    /// SMC's (its order is always [`Order::Chromosome`]).
    pub smc: SmcSettings,
    /// SOSMC's (its order is always [`Order::Stochastic`]).
    pub sosmc: SmcSettings,
    /// RJMCMC's.
    pub rjmcmc: McmcSettings,
}

impl Presets {
    /// The GA's settings `ga`, SMC's and SOSMC's from `smc` in their orders, and RJMCMC's
    /// `rjmcmc`: a paper scene's configuration files, as a published generator's module
    /// gives them.
    ///
    /// ```
    /// use generators::{Presets, tree};
    /// use shapegen_runtime::optimize::Order;
    ///
    /// let p = Presets::paper(tree::paper_ga(), tree::paper_smc, tree::paper_rjmcmc());
    /// assert_eq!(p.sosmc.order, Order::Stochastic);
    /// assert_eq!(p, tree::presets());
    /// ```
    pub fn paper(ga: GaSettings, smc: fn(Order) -> SmcSettings, rjmcmc: McmcSettings) -> Self {
        Presets {
            ga,
            smc: smc(Order::Chromosome),
            sosmc: smc(Order::Stochastic),
            rjmcmc,
        }
    }
}

impl Default for Presets {
    /// Every method's own defaults.
    fn default() -> Self {
        let smc = SmcSettings::default();
        Presets {
            ga: GaSettings::default(),
            smc: SmcSettings {
                order: Order::Chromosome,
                ..smc
            },
            sosmc: SmcSettings {
                order: Order::Stochastic,
                ..smc
            },
            rjmcmc: McmcSettings::default(),
        }
    }
}
