//! Counting one model on the CPU: bitsets of the voxels covered and covered again, whose
//! reset costs what the model covered.

use glam::{DVec3, Vec3};

use super::counts::VolumeCounts;
use super::parity::{Bounds, Voxelizer};
use super::parts::PartKind;
use super::quant::{Placement, QuantBox, quantize, usable_linear, voxels_of_volume};
use super::scorer::VolumeScorer;
use super::scratch::VolumeScratch;
use super::span::span_out_of_grid;
use crate::geometry::Instance;

/// Facet corners are snapped to `1 / FACET_SNAP` of a voxel.
const FACET_SNAP: f64 = 4096.0;

/// Where the lattice points one instance covers go: a model's running counts, in one
/// form or another.
pub(super) trait Lattice {
    /// The instance's span holds `n` voxels outside the grid.
    fn span(&mut self, n: u64);
    /// `n` covered lattice points lie outside the grid.
    fn outside(&mut self, n: u64);
    /// In-grid voxels `first..=last` (flat indices, [`Grid::index`](super::Grid::index))
    /// are covered.
    fn voxels(&mut self, first: usize, last: usize);
}

/// The running counts of one model, counted from nothing in bitsets.
struct Tally<'a> {
    scorer: &'a VolumeScorer,
    covered: &'a mut [u64],
    twice: &'a mut [u64],
    touched: &'a mut Vec<u32>,
    counts: VolumeCounts,
}

impl Lattice for Tally<'_> {
    fn span(&mut self, n: u64) {
        let c = &mut self.counts;
        c.span_out_of_grid = c.span_out_of_grid.saturating_add(n);
    }

    fn outside(&mut self, n: u64) {
        let c = &mut self.counts;
        c.out_of_grid_hits = c.out_of_grid_hits.saturating_add(n);
    }

    #[inline]
    fn voxels(&mut self, first: usize, last: usize) {
        let per = self.scorer.class_stride;
        for (w, mask) in word_masks(first, last) {
            let old = self.covered[w];
            if old == 0 {
                self.touched.push(w as u32);
            }
            self.covered[w] = old | mask;
            let again = old & mask;
            if again != 0 {
                self.counts.overlap_hits += u64::from(again.count_ones());
                let twice = self.twice[w];
                self.twice[w] = twice | again;
                self.counts.overlap_voxels += u64::from((again & !twice).count_ones());
            }
            let new = mask & !old;
            let mut rest = u64::from(new.count_ones());
            let masks = &self.scorer.class_bits[w * per..(w + 1) * per];
            for (count, &m) in self.counts.classes.iter_mut().zip(masks) {
                let n = u64::from((new & m).count_ones());
                *count += n;
                rest -= n;
            }
            self.counts.classes[per] += rest;
        }
    }
}

/// The words of voxels `first..=last`, each with the mask of its bits among them.
#[inline]
pub(super) fn word_masks(first: usize, last: usize) -> impl Iterator<Item = (usize, u64)> {
    let (w0, w1) = (first / 64, last / 64);
    (w0..=w1).map(move |w| {
        let mut mask = !0u64;
        if w == w0 {
            mask &= !0 << (first % 64);
        }
        if w == w1 {
            mask &= !0 >> (63 - last % 64);
        }
        (w, mask)
    })
}

impl VolumeScorer {
    /// Hands what `instance` covers to `out`: its span outside the grid, then its covered
    /// lattice points, row by row. What an instance covers depends on the instance alone.
    pub(super) fn walk(
        &self,
        instance: &Instance,
        voxelizer: &mut Voxelizer,
        out: &mut impl Lattice,
    ) {
        let Some(part) = self.parts.get(instance.mesh.0 as usize) else {
            return; // ids the grammar lacks cover nothing
        };
        out.span(span_out_of_grid(&self.grid, part, &instance.transform));
        match part {
            // Covered together with the model's other facets: see walk_facets.
            PartKind::Facet => {}
            PartKind::Box => match quantize(&self.grid, &instance.transform) {
                Placement::Nothing => {}
                Placement::Oversize(n) => out.outside(n),
                Placement::Box(q) => self.quant_box(&q, out),
            },
            &PartKind::Solid { volume, .. } => {
                let t = &instance.transform;
                let Some((m, shift)) = usable_linear(t.matrix3, Vec3::from(t.translation)) else {
                    return;
                };
                let grid = &self.grid;
                let mesh = &self.meshes[instance.mesh];
                let place = |p: Vec3| grid.to_lattice(m * p.as_dvec3() + shift);
                let run = voxelizer.run(mesh, place, Bounds::Lattice, |j, k, a, b| {
                    self.row(out, j, k, a, b)
                });
                if run.is_err() {
                    out.outside(voxels_of_volume(grid, volume * m.determinant().abs()));
                }
            }
        }
    }

    /// Hands what the facets among `instances` cover to `out`, together: each lattice
    /// point once for every closed facet surface that holds it (their winding number).
    /// Facets beyond the rasterisation limits count as many lattice points outside the
    /// grid as the voxels of the volume they enclose.
    pub(super) fn walk_facets(
        &self,
        instances: &[Instance],
        voxelizer: &mut Voxelizer,
        out: &mut impl Lattice,
    ) {
        if !self.parts.contains(&PartKind::Facet) {
            return; // the grammar has no facets: the instance path alone
        }
        let grid = &self.grid;
        // The corners `a`, `a + u`, `a + v` in f64 (exactly the sums of the transform's
        // f32 columns).
        let triangles = || {
            instances.iter().filter(|i| self.is_facet(i)).map(|i| {
                let t = &i.transform;
                let a = Vec3::from(t.translation).as_dvec3();
                let [u, v] = [t.matrix3.x_axis, t.matrix3.y_axis].map(|c| Vec3::from(c).as_dvec3());
                [a, a + u, a + v]
            })
        };
        // A corner two facets share is placed from each facet's own columns, which can
        // differ in the last bits: snapped to 1/4096 of a voxel, both copies are one
        // point again, and the surface stays closed to the rays.
        let snap = |p: DVec3| (grid.to_lattice(p) * FACET_SNAP).round() / FACET_SNAP;
        let lattice = triangles().map(|t| t.map(snap));
        let run = voxelizer.run_winding(lattice, Bounds::Lattice, |j, k, a, b| {
            self.row(out, j, k, a, b)
        });
        if run.is_err() {
            let volume: f64 = triangles().map(|[a, b, c]| a.dot(b.cross(c)) / 6.0).sum();
            out.outside(voxels_of_volume(grid, volume.abs()));
        }
    }

    /// Whether `instance` is a facet, counted with the model's other facets.
    #[inline]
    pub(super) fn is_facet(&self, instance: &Instance) -> bool {
        self.part(instance.mesh) == Some(&PartKind::Facet)
    }

    /// Covers lattice points `(first..=last, j, k)`.
    #[inline]
    fn row(&self, out: &mut impl Lattice, j: i64, k: i64, first: i64, last: i64) {
        let len = (last - first + 1) as u64;
        let [nx, ny, nz] = self.grid.resolution().map(i64::from);
        if !(0..ny).contains(&j) || !(0..nz).contains(&k) {
            out.outside(len);
            return;
        }
        let (a, b) = (first.max(0), last.min(nx - 1));
        if a > b {
            out.outside(len);
            return;
        }
        let outside = len - (b - a + 1) as u64;
        if outside > 0 {
            out.outside(outside);
        }
        let base = (j + ny * k) * nx;
        out.voxels((base + a) as usize, (base + b) as usize);
    }

    /// Covers what box `q` covers.
    fn quant_box(&self, q: &QuantBox, out: &mut impl Lattice) {
        let [i0, j0, k0, _] = q.corner.map(i64::from);
        for k in 0..q.extent[2] {
            for j in 0..q.extent[1] {
                if let Some((a, b)) = q.row(j, k) {
                    let (a, b) = (i0 + i64::from(a), i0 + i64::from(b));
                    self.row(out, j0 + i64::from(j), k0 + i64::from(k), a, b);
                }
            }
        }
    }
}

impl VolumeScorer {
    /// Counts the model made of `instances` with `scratch`, leaving it cleared; with
    /// `keep`, also writes the covered in-grid voxels there as a bitset.
    pub(crate) fn count_model(
        &self,
        instances: &[Instance],
        scratch: &mut VolumeScratch,
        keep: Option<&mut Vec<u64>>,
    ) -> VolumeCounts {
        let VolumeScratch {
            covered,
            twice,
            touched,
            voxelizer,
            dilated,
        } = scratch;
        let mut tally = Tally {
            scorer: self,
            covered,
            twice,
            touched,
            counts: VolumeCounts::default(),
        };
        for instance in instances {
            self.walk(instance, voxelizer, &mut tally);
        }
        self.walk_facets(instances, voxelizer, &mut tally);
        let counts = self.add_surface(
            tally.counts,
            covered,
            touched.iter().map(|&w| w as usize),
            dilated,
        );
        if let Some(out) = keep {
            out.clear();
            out.resize(covered.len(), 0);
            for &w in touched.iter() {
                out[w as usize] = covered[w as usize];
            }
        }
        for &w in touched.iter() {
            covered[w as usize] = 0;
            twice[w as usize] = 0;
        }
        touched.clear();
        self.with_totals(counts)
    }

    /// `counts` with `inside` and `outside` summed from its classes.
    pub(crate) fn with_totals(&self, mut counts: VolumeCounts) -> VolumeCounts {
        let (mut inside, mut outside) = (0, 0);
        for (c, &n) in counts
            .classes
            .iter()
            .enumerate()
            .take(self.classes.weights().len())
        {
            if self.classes.is_target(c) {
                inside += n;
            } else {
                outside += n;
            }
        }
        counts.inside = inside;
        counts.outside = outside;
        counts
    }
}
