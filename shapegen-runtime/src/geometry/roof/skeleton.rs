//! The weighted straight skeleton of a polygon, swept as a roof surface.
//!
//! Every edge moves inward along its normal at its own speed (its weight), keeping its
//! direction; the corners slide along the moving edges. At time `t` the moving outline
//! stands at height `t * slope`, so each edge sweeps a plane of slope `slope / weight`
//! (vertical for weight 0, a gable end). The sweep stops at events: an edge shrinks to
//! nothing (its corners merge), or a reflex corner reaches another edge (the outline
//! splits in two). Between events every edge sweeps a planar quad, which is added to
//! the solid; welding and T-junction splitting in [`Solid`] stitch the strips together.
//!
//! Events are found by checking every edge and every reflex corner against every edge
//! at each step: quadratic per event, meant for the tens of points of a footprint.

use glam::DVec2;

use super::super::polygon::{EPS, Polygon};
use super::super::solid::Solid;
use super::shape::RoofError;

/// An edge of the polygon as it moves: unit direction, unit inward normal, speed.
struct Line {
    dir: DVec2,
    normal: DVec2,
    weight: f64,
}

/// A corner of a moving outline.
#[derive(Clone, Copy)]
struct Corner {
    /// Position at the current time.
    at: DVec2,
    /// Velocity, from the lines of the edges in and out.
    velocity: DVec2,
    /// The polygon edge the outline's edge from this corner to the next lies on.
    edge: usize,
    /// Whether this is still one of the polygon's own corners.
    original: bool,
}

/// What happens next.
enum Event {
    /// The edge from corner `at` of outline `outline` to the next shrinks to nothing.
    Collapse { outline: usize, at: usize },
    /// Reflex corner `corner` reaches the edge from corner `edge` to the next.
    Split {
        outline: usize,
        corner: usize,
        edge: usize,
    },
}

/// What the sweep learned besides the surface.
pub(super) struct Sweep {
    /// For each polygon edge, whether its face is a triangle: the edge shrank to a point
    /// while both its ends were still the polygon's corners (the ends of a hip roof).
    pub(super) triangle_face: Vec<bool>,
}

/// Sweeps the roof surface over `polygon` into `solid`: edges move at `weights` (one per
/// edge, each `>= 0`), the outline at time `t` stands at height `z0 + t * slope`.
pub(super) fn sweep(
    polygon: &Polygon,
    weights: &[f64],
    z0: f64,
    slope: f64,
    solid: &mut Solid,
) -> Result<Sweep, RoofError> {
    let n = polygon.len();
    let lines: Vec<Line> = (0..n)
        .map(|i| {
            let (a, b) = polygon.edge(i);
            let dir = (b - a).normalize();
            Line {
                dir,
                normal: dir.perp(),
                weight: weights[i],
            }
        })
        .collect();
    let tolerance = 1e-9 * polygon.scale();
    let mut sweep = Sweep {
        triangle_face: vec![false; n],
    };
    let mut outlines = vec![
        polygon
            .points()
            .iter()
            .enumerate()
            .map(|(i, &at)| Corner {
                at,
                velocity: DVec2::ZERO,
                edge: i,
                original: true,
            })
            .collect::<Vec<_>>(),
    ];
    let mut t = 0.0;
    let height = |t: f64| z0 + t * slope;
    for _ in 0..(8 * n * n + 64) {
        tidy(&mut outlines, &lines, tolerance, &mut sweep.triangle_face);
        if outlines.is_empty() {
            return Ok(sweep);
        }
        let Some((dt, event)) = next_event(&outlines, &lines, tolerance) else {
            // Nothing moves any more (every edge left has weight 0): close the top flat.
            for outline in &outlines {
                let points: Vec<DVec2> = outline.iter().map(|c| c.at).collect();
                if let Ok(top) = Polygon::from_f64(&points) {
                    solid.cap(&top, true, |_| height(t));
                }
            }
            return Ok(sweep);
        };
        let next_t = t + dt;
        for outline in &mut outlines {
            advance(outline, dt, [height(t), height(next_t)], solid);
        }
        t = next_t;
        happen(event, &mut outlines, &mut sweep.triangle_face);
    }
    Err(RoofError::Degenerate {
        points: polygon.len(),
    })
}

/// Moves the corners of `outline` on by `dt`, adding the quad each of its edges sweeps
/// from height `z[0]` to `z[1]` to `solid` (none when `dt` is 0).
fn advance(outline: &mut [Corner], dt: f64, z: [f64; 2], solid: &mut Solid) {
    let moved: Vec<DVec2> = outline.iter().map(|c| c.at + c.velocity * dt).collect();
    if dt > 0.0 {
        let m = outline.len();
        for i in 0..m {
            let j = (i + 1) % m;
            solid.quad(
                outline[i].at.extend(z[0]),
                outline[j].at.extend(z[0]),
                moved[j].extend(z[1]),
                moved[i].extend(z[1]),
            );
        }
    }
    for (c, at) in outline.iter_mut().zip(moved) {
        c.at = at;
    }
}

/// Changes `outlines` as `event` does: a collapsing edge's corners merge (marking its
/// polygon edge's face a triangle in `triangle_face` when both were the polygon's own
/// corners), a split cuts an outline in two at the reflex corner.
fn happen(event: Event, outlines: &mut Vec<Vec<Corner>>, triangle_face: &mut [bool]) {
    match event {
        Event::Collapse { outline, at } => {
            let o = &mut outlines[outline];
            let m = o.len();
            let next = (at + 1) % m;
            let (a, b) = (o[at], o[next]);
            if a.original && b.original {
                triangle_face[a.edge] = true;
            }
            o[next] = Corner {
                at: (a.at + b.at) / 2.0,
                original: false,
                ..b
            };
            o.remove(at);
        }
        Event::Split {
            outline,
            corner,
            edge,
        } => {
            let o = outlines.swap_remove(outline);
            let m = o.len();
            let r = o[corner];
            let hit = Corner {
                original: false,
                ..r
            };
            // One side: the corner with its edge out, on to the hit edge's start.
            let mut first = vec![hit];
            let mut k = (corner + 1) % m;
            loop {
                first.push(o[k]);
                if k == edge {
                    break;
                }
                k = (k + 1) % m;
            }
            // The other: the corner on the hit edge, on to the corner before.
            let mut second = vec![Corner {
                edge: o[edge].edge,
                ..hit
            }];
            let mut k = (edge + 1) % m;
            while k != corner {
                second.push(o[k]);
                k = (k + 1) % m;
            }
            outlines.push(first);
            outlines.push(second);
        }
    }
}

/// Drops corners that fold straight back and outlines with no area left, and sets every
/// corner's velocity.
///
/// An outline dropped for having no area has shrunk to a point or a line: its edges of
/// no length whose ends are the polygon's corners have shrunk to a point, as a
/// collapsing edge does, and are marked in `triangle_face`.
fn tidy(
    outlines: &mut Vec<Vec<Corner>>,
    lines: &[Line],
    tolerance: f64,
    triangle_face: &mut [bool],
) {
    for o in outlines.iter_mut() {
        // A corner whose edges in and out run opposite ways is a spike of no width (no
        // wider than the tolerance the polygon was cleaned with).
        let mut k = 0;
        while o.len() >= 3 && k < o.len() {
            let m = o.len();
            let before = &lines[o[(k + m - 1) % m].edge];
            let after = &lines[o[k].edge];
            if before.dir.dot(after.dir) < 0.0 && before.dir.perp_dot(after.dir).abs() < EPS {
                // The edge left, from the corner before to the one after, runs along
                // whichever of the two goes its way.
                let (p, q) = ((k + m - 1) % m, (k + 1) % m);
                if (o[q].at - o[p].at).dot(before.dir) < 0.0 {
                    o[p].edge = o[k].edge;
                }
                o.remove(k);
            } else {
                k += 1;
            }
        }
    }
    outlines.retain(|o| {
        let points: Vec<DVec2> = o.iter().map(|c| c.at).collect();
        let Some(&first) = points.first() else {
            return false;
        };
        let (lo, hi) = points
            .iter()
            .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let keep = points.len() >= 3
            && super::super::polygon::signed_area(&points)
                > tolerance * (hi - lo).length().max(tolerance);
        if !keep {
            let m = o.len();
            for k in 0..m {
                let (a, b) = (o[k], o[(k + 1) % m]);
                if a.original && b.original && (b.at - a.at).length() <= tolerance {
                    triangle_face[a.edge] = true;
                }
            }
        }
        keep
    });
    for o in outlines.iter_mut() {
        let m = o.len();
        for k in 0..m {
            let before = &lines[o[(k + m - 1) % m].edge];
            let after = &lines[o[k].edge];
            o[k].velocity = velocity(before, after);
        }
    }
}

/// The velocity of a corner between two moving edges: on both their lines.
fn velocity(a: &Line, b: &Line) -> DVec2 {
    let det = a.normal.perp_dot(b.normal);
    if det.abs() > 1e-12 {
        // Solve [a.normal; b.normal] v = [a.weight; b.weight].
        DVec2::new(
            (a.weight * b.normal.y - b.weight * a.normal.y) / det,
            (a.normal.x * b.weight - b.normal.x * a.weight) / det,
        )
    } else {
        // Edges on one line (or opposite: a spike, dropped by `tidy`): move with them.
        a.normal * (a.weight + b.weight) / 2.0
    }
}

/// The earliest event of all outlines, and the time until it; `None` when nothing will
/// happen.
fn next_event(outlines: &[Vec<Corner>], lines: &[Line], tolerance: f64) -> Option<(f64, Event)> {
    let mut best: Option<(f64, Event)> = None;
    let mut offer = |dt: f64, e: Event| {
        if dt.is_finite() && best.as_ref().is_none_or(|(b, _)| dt < *b) {
            best = Some((dt.max(0.0), e));
        }
    };
    for (oi, o) in outlines.iter().enumerate() {
        let m = o.len();
        for i in 0..m {
            let (a, b) = (o[i], o[(i + 1) % m]);
            let dir = lines[a.edge].dir;
            let length = (b.at - a.at).dot(dir);
            let rate = (b.velocity - a.velocity).dot(dir);
            if length <= tolerance && rate <= 0.0 {
                offer(0.0, Event::Collapse { outline: oi, at: i });
            } else if rate < 0.0 {
                offer(-length / rate, Event::Collapse { outline: oi, at: i });
            }
        }
        for r in 0..m {
            let before = &lines[o[(r + m - 1) % m].edge];
            let after = &lines[o[r].edge];
            if before.dir.perp_dot(after.dir) >= 0.0 {
                continue; // not reflex
            }
            let c = o[r];
            for j in 0..m {
                let k = (j + 1) % m;
                // Not the corner's own edges (in: ends at r; out: starts at r).
                if j == r || k == r {
                    continue;
                }
                let line = &lines[o[j].edge];
                let gap = (c.at - o[j].at).dot(line.normal);
                let closing = c.velocity.dot(line.normal) - line.weight;
                if closing >= -1e-12 || gap < -tolerance {
                    continue;
                }
                let dt = gap.max(0.0) / -closing;
                let hit = c.at + c.velocity * dt;
                let start = o[j].at + o[j].velocity * dt;
                let end = o[k].at + o[k].velocity * dt;
                let along = (hit - start).dot(line.dir);
                let length = (end - start).dot(line.dir);
                if along >= -tolerance && along <= length + tolerance {
                    offer(
                        dt,
                        Event::Split {
                            outline: oi,
                            corner: r,
                            edge: j,
                        },
                    );
                }
            }
        }
    }
    best
}
