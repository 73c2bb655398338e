//! Genomes from nothing: random genomes grown to a target length (the GA's initial
//! population) and uncontrolled samples of the generator's own distribution.

use rand::Rng;

use super::operators::{OperatorVariant, Operators};
use super::weight::{below, chance};
use crate::derive::Grammar;
use crate::genome::{Genome, depths};
use crate::graph::HEADER_WORDS;

impl<G: Grammar> Operators<G> {
    /// A random genome: the axiom, then weighted grows until a target length drawn by
    /// [`random_len`](Self::random_len) or until nothing can grow.
    ///
    /// Gives exactly the genome that drawing the length, then [`Genome::axiom`], then
    /// calling [`grow`](Self::grow) until that length would give with the same RNG, in
    /// O(G log G) instead of O(G²): open links sit in a Fenwick tree of their weights.
    /// The genome is shorter than `min_len` only if no genome within the depth limit can
    /// be that long.
    ///
    /// With the [`Original`](super::OperatorVariant::Original) rules it is the original's
    /// `createRandomGenome` instead: the axiom, then exactly `initial_len - 1` of the
    /// original's grows, whatever the limits (fewer only if nothing can grow), so the
    /// genome has exactly `initial_len` genes. O(W + G²) with a small constant.
    ///
    /// ```
    /// # use rand::SeedableRng;
    /// # use shapegen_runtime::genome::Limits;
    /// # use shapegen_runtime::ops::Operators;
    /// # shapegen_runtime::generator! {
    /// #     pub Chain {
    /// #         axiom Start;
    /// #         node Start { children { first: Seg = 0.9 } }
    /// #         node Seg {
    /// #             params { len: f32 ~ uniform(0.5, 1.5) }
    /// #             children { next: Seg = 0.5, side: Seg = 0.25 }
    /// #             derive(s) {
    /// #                 use shapegen_runtime::prelude::{CUBE, vec3};
    /// #                 let s = s.resize(vec3(1.0, len, 1.0));
    /// #                 s.emit(CUBE);
    /// #                 if let Some(next) = next {
    /// #                     s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
    /// #                 }
    /// #                 if let Some(side) = side {
    /// #                     s.rotate_z(0.5).translate(vec3(0.0, s.size().y, 0.0)).derive(side);
    /// #                 }
    /// #             }
    /// #         }
    /// #     }
    /// # }
    /// let mut ops = Operators::<Chain>::new(Limits::new(1, 500, 64)?)?;
    /// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2);
    /// let g = ops.random(100, &mut rng);
    /// assert!((50..=150).contains(&g.len()));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn random(&mut self, initial_len: u32, rng: &mut impl Rng) -> Genome<G> {
        let mut g = Genome::from_parts(Vec::new(), 0);
        self.random_into(initial_len, &mut g, rng);
        g
    }

    /// As [`random`](Self::random), writing into `out` and reusing its allocation.
    pub fn random_into(&mut self, initial_len: u32, out: &mut Genome<G>, rng: &mut impl Rng) {
        if self.variant == OperatorVariant::Original {
            out.reset_to_axiom(rng);
            self.reserve_grows(out, initial_len);
            self.grow_original(out, initial_len.saturating_sub(1), rng);
            return;
        }
        let target = self.random_len(initial_len, rng);
        out.reset_to_axiom(rng);
        self.reserve_grows(out, target);
        self.grow_to(out, target, rng);
    }

    /// Reserves room in `genome` for growing to `target_len` genes, so that its buffer is
    /// allocated once.
    fn reserve_grows(&self, genome: &mut Genome<G>, target_len: u32) {
        let grows = target_len.saturating_sub(genome.len) as usize;
        genome.words.reserve(grows * self.child_words as usize);
    }

    /// The target length of a weighted random genome: uniform over `[L/2, 3L/2]` for
    /// `L = initial_len` (integer halves), clamped into `[min_len, max_len]`.
    pub fn random_len(&self, initial_len: u32, rng: &mut impl Rng) -> u32 {
        let lo = initial_len / 2;
        let hi = initial_len.saturating_add(initial_len / 2);
        let t = lo + below(rng, u64::from(hi - lo) + 1) as u32;
        t.clamp(self.limits.min_len.max(1), self.limits.max_len)
    }

    /// Grows `genome` until it holds `target_len` genes (at most `max_len` with the
    /// weighted rules) or nothing can grow; returns the number of genes added. Each step
    /// has exactly the distribution of [`grow`](Self::grow), and the same RNG gives the
    /// same genome as calling `grow` that many times. O(G log G) weighted, O(W + G²)
    /// original.
    pub fn grow_to(&mut self, genome: &mut Genome<G>, target_len: u32, rng: &mut impl Rng) -> u32 {
        if self.variant == OperatorVariant::Original {
            let steps = target_len.saturating_sub(genome.len);
            return self.grow_original(genome, steps, rng);
        }
        let target = target_len.min(self.limits.max_len);
        if genome.len >= target {
            return 0;
        }
        let max_depth = self.limits.max_depth;
        let s = &mut self.s;
        s.fenwick.clear();
        s.owners.clear();
        depths::<G>(&genome.words, &mut s.depth);
        // Open links in buffer order, as grow weighs them; filled ones weigh nothing.
        let mut pos = 0u32;
        while (pos as usize) < genome.words.len() {
            let k = self.kinds[genome.words[pos as usize] as usize];
            let d = s.depth[pos as usize];
            if d < max_depth {
                for link in 0..k.links {
                    let empty = genome.words[(pos + HEADER_WORDS + link) as usize] == 0;
                    let w = self.links[(k.first_link + link) as usize].grow;
                    s.fenwick.push(if empty { w } else { 0 });
                    s.owners.push((pos, link, d));
                }
            }
            pos += k.gene_words;
        }
        let start = genome.len;
        while genome.len < target && s.fenwick.total() > 0 {
            let i = s.fenwick.find(below(rng, s.fenwick.total()));
            let (pos, link, d) = s.owners[i];
            let k = self.kinds[genome.words[pos as usize] as usize];
            let l = self.links[(k.first_link + link) as usize];
            s.fenwick.sub(i, l.grow);
            let child = self.fresh.push(genome, l.child, Some((pos, link)), rng);
            if d + 1 < max_depth {
                let ck = self.kinds[l.child as usize];
                for link in 0..ck.links {
                    s.fenwick
                        .push(self.links[(ck.first_link + link) as usize].grow);
                    s.owners.push((child, link, d + 1));
                }
            }
        }
        genome.len - start
    }

    /// An uncontrolled sample: the generator's own distribution. Starting from the
    /// axiom, visits genes in creation order (breadth first) and expresses each link
    /// with its probability, never below the maximum depth and stopping at the maximum
    /// length. `min_len` is not applied (see [`sample_at_least`](Self::sample_at_least)).
    /// O(W).
    ///
    /// ```
    /// # use rand::SeedableRng;
    /// # use shapegen_runtime::genome::Limits;
    /// # use shapegen_runtime::ops::Operators;
    /// # shapegen_runtime::generator! {
    /// #     pub Chain {
    /// #         axiom Start;
    /// #         node Start { children { first: Seg = 0.9 } }
    /// #         node Seg {
    /// #             params { len: f32 ~ uniform(0.5, 1.5) }
    /// #             children { next: Seg = 0.5, side: Seg = 0.25 }
    /// #             derive(s) {
    /// #                 use shapegen_runtime::prelude::{CUBE, vec3};
    /// #                 let s = s.resize(vec3(1.0, len, 1.0));
    /// #                 s.emit(CUBE);
    /// #                 if let Some(next) = next {
    /// #                     s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
    /// #                 }
    /// #                 if let Some(side) = side {
    /// #                     s.rotate_z(0.5).translate(vec3(0.0, s.size().y, 0.0)).derive(side);
    /// #                 }
    /// #             }
    /// #         }
    /// #     }
    /// # }
    /// let mut ops = Operators::<Chain>::new(Limits::new(1, 100, 6)?)?;
    /// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
    /// let g = ops.sample(&mut rng);
    /// assert!(g.depth() <= 6 && g.len() <= 100);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn sample(&mut self, rng: &mut impl Rng) -> Genome<G> {
        let mut g = Genome::from_parts(Vec::new(), 0);
        self.sample_into(&mut g, rng);
        g
    }

    /// As [`sample`](Self::sample), writing into `out` and reusing its allocation.
    pub fn sample_into(&mut self, out: &mut Genome<G>, rng: &mut impl Rng) {
        out.reset_to_axiom(rng);
        let (max_len, max_depth) = (self.limits.max_len, self.limits.max_depth);
        let queue = &mut self.s.owners;
        queue.clear();
        queue.push((0, 0, 1));
        let mut head = 0;
        'genes: while head < queue.len() {
            let (pos, _, d) = queue[head];
            head += 1;
            if d >= max_depth {
                continue;
            }
            let k = self.kinds[out.words[pos as usize] as usize];
            for link in 0..k.links {
                if out.len >= max_len {
                    break 'genes;
                }
                let l = self.links[(k.first_link + link) as usize];
                if chance(rng, l.grow) {
                    let child = self.fresh.push(out, l.child, Some((pos, link)), rng);
                    queue.push((child, 0, d + 1));
                }
            }
        }
    }

    /// An uncontrolled sample of at least `min_len` genes: the generator's distribution
    /// conditioned on the limits, by drawing [`sample`](Self::sample)s until one is long
    /// enough, at most `attempts` times.
    pub fn sample_at_least(&mut self, attempts: u32, rng: &mut impl Rng) -> Option<Genome<G>> {
        let mut g = Genome::from_parts(Vec::new(), 0);
        for _ in 0..attempts {
            self.sample_into(&mut g, rng);
            if g.len >= self.limits.min_len {
                return Some(g);
            }
        }
        None
    }
}
