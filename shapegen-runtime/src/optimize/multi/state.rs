//! The checkpoint of the multi-objective GA ([`MultiGaState`]), in the layout its files
//! have always had: the progress's counters and record written inline, the record's
//! senses before the population, its archive, best values and history after.

use serde::de::Deserializer;
use serde::ser::{SerializeStruct, Serializer};
use serde::{Deserialize, Serialize};

use super::record::{Front, Member, MultiHistoryEntry};
use super::settings::MultiGaSettings;
use crate::derive::Grammar;
use crate::evaluate::Sense;
use crate::genome::{Genome, Limits};
use crate::optimize::fitness::bits_vec;
use crate::optimize::run::Progress;

crate::checkpoint! {
    @struct
    /// A checkpoint of a [`MultiGa`](super::MultiGa): serialize it (e.g. with
    /// `serde_json`) and give it to [`MultiGa::resume`](crate::optimize::Optimizer::resume) to go on
    /// exactly as an
    /// uninterrupted run would. It reads and writes the fields of its progress inline:
    /// `seed`, `generation`, `evaluations`, `elapsed_s` and `senses` after the limits,
    /// then the population and its values, then `archive`, `best` and `history`.
    pub struct MultiGaState<G>: MultiGaSettings, Front<G> {
        /// The current population.
        pub population: Vec<Genome<G>>,
        /// Its objective values, row-major.
        pub values: Vec<f64>,
    }
}

/// The fields of a [`MultiGaState`] as files hold them.
#[derive(Deserialize)]
#[serde(
    rename = "MultiGaState",
    deny_unknown_fields,
    bound(deserialize = "G: Grammar")
)]
struct Flat<G> {
    settings: MultiGaSettings,
    limits: Limits,
    seed: u64,
    generation: u64,
    evaluations: u64,
    elapsed_s: f64,
    senses: Vec<Sense>,
    population: Vec<Genome<G>>,
    #[serde(with = "bits_vec")]
    values: Vec<f64>,
    archive: Vec<Member<G>>,
    #[serde(with = "bits_vec")]
    best: Vec<f64>,
    history: Vec<MultiHistoryEntry>,
}

impl<'de, G: Grammar> Deserialize<'de> for MultiGaState<G> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let f = Flat::<G>::deserialize(d)?;
        let record = Front {
            senses: f.senses,
            archive: f.archive,
            best: f.best,
            history: f.history,
        };
        Ok(MultiGaState {
            settings: f.settings,
            limits: f.limits,
            progress: Progress {
                seed: f.seed,
                generation: f.generation,
                evaluations: f.evaluations,
                elapsed_s: f.elapsed_s,
                record,
            },
            population: f.population,
            values: f.values,
        })
    }
}

impl<G: Grammar> Serialize for MultiGaState<G> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (p, r) = (&self.progress, &self.progress.record);
        let mut out = s.serialize_struct("MultiGaState", 12)?;
        out.serialize_field("settings", &self.settings)?;
        out.serialize_field("limits", &self.limits)?;
        out.serialize_field("seed", &p.seed)?;
        out.serialize_field("generation", &p.generation)?;
        out.serialize_field("evaluations", &p.evaluations)?;
        out.serialize_field("elapsed_s", &p.elapsed_s)?;
        out.serialize_field("senses", &r.senses)?;
        out.serialize_field("population", &self.population)?;
        out.serialize_field("values", &Bits(&self.values))?;
        out.serialize_field("archive", &r.archive)?;
        out.serialize_field("best", &Bits(&r.best))?;
        out.serialize_field("history", &r.history)?;
        out.end()
    }
}

/// Fitness values written as their bits.
struct Bits<'a>(&'a [f64]);

impl Serialize for Bits<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        bits_vec::serialize(self.0, s)
    }
}
