//! The generative variant's growth ([`SmcVariant::Generative`](super::SmcVariant)):
//! particles grow as the generator would, a step lasting until new geometry appears.

use rand::{Rng, RngExt};

use super::super::grow::{depth_of, expand, link_facts, open_links};
use super::settings::{Cursor, Order, SmcSettings};
use crate::derive::Grammar;
use crate::genome::{Genome, Limits, node_of};
use crate::geometry::Instance;
use crate::graph::HEADER_WORDS;

/// Per-thread scratch of a step.
#[derive(Default)]
pub(super) struct Scratch {
    instances: Vec<Instance>,
    depth: Vec<u32>,
    open: Vec<(u32, u32)>,
}

/// Grows one particle until it emits new geometry, `max_grows_per_step` genes were
/// added, or nothing can grow; returns whether it may grow further (`false` once
/// nothing could).
pub(super) fn advance<G: Grammar>(
    settings: &SmcSettings,
    limits: &Limits,
    g: &mut Genome<G>,
    c: &mut Cursor,
    s: &mut Scratch,
    rng: &mut impl Rng,
) -> bool {
    for _ in 0..settings.max_grows_per_step {
        let grown = match settings.order {
            Order::Chromosome => next_in_order(limits, g, c, rng),
            Order::Stochastic => {
                open_links(g, limits, &mut s.depth, &mut s.open);
                if s.open.is_empty() {
                    false
                } else {
                    let (pos, link) = s.open[rng.random_range(0..s.open.len())];
                    expand(g, limits, pos, link, rng).is_some()
                }
            }
        };
        if !grown {
            return false;
        }
        g.derive_into(&mut s.instances);
        let emitted = s.instances.len() as u32;
        if emitted > c.emitted {
            c.emitted = emitted;
            return true;
        }
        c.emitted = emitted;
    }
    true
}

/// Decides links in chromosome order from the cursor until one is expressed; returns
/// `false` when every link has been decided or the genome is at its maximum length.
fn next_in_order<G: Grammar>(
    limits: &Limits,
    g: &mut Genome<G>,
    c: &mut Cursor,
    rng: &mut impl Rng,
) -> bool {
    while (c.pos as usize) < g.words().len() {
        let kind = g.words()[c.pos as usize];
        let node = node_of::<G>(kind);
        if c.link >= node.links || depth_of(g.words(), c.pos) >= limits.max_depth {
            c.pos += node.gene_words();
            c.link = 0;
            continue;
        }
        let link = c.link;
        c.link += 1;
        if g.words()[(c.pos + HEADER_WORDS + link) as usize] != 0 {
            continue;
        }
        if rng.random::<f32>() < link_facts::<G>(kind, link).0 {
            return expand(g, limits, c.pos, link, rng).is_some();
        }
    }
    false
}
