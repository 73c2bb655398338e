//! Evolves roofed buildings on an L-shaped lot: the project's `scenes/lot_building.toml`,
//! whose lot is `scenes/lots/l_lot.geojson`. Its four objectives ask for a footprint
//! seen from above and a silhouette seen from the front (both of one building of the lot
//! building generator on that lot), a window-to-wall ratio near 0.35 and roofs pitched
//! near 35 degrees. The multi-objective GA (Pareto ranking with crowding, a penalty for
//! clones) runs the scene's generations, or the time budget if that comes first, and
//! keeps every non-dominated building it finds.
//!
//! It writes `out/building`: `front.csv` (each front member's objective values),
//! `contact_sheet.png` (up to 24 of the front's buildings, evenly thinned, in the csv's
//! order, through one camera),
//! `front_NNN.glb`, and the building whose footprint and front silhouette match best as
//! `best.obj` (with `best.mtl`), `best.glb` and `best.png`, with separate `wall`, `roof`,
//! `window`, `door` and `slab` materials.
//!
//! ```sh
//! cargo run --release --example building          # writes out/building
//! cargo run --release --example building -- 20    # a 20-second budget instead of 90
//! ```

use std::path::Path;
use std::time::Duration;

use anyhow::Context;
use generators::LotBuilding;
use shapegen::export::{ContactSheet, ExportError, Model, Palette, Preview, save_glb, save_obj};
use shapegen::geometry::{BoundMeshes, Instance};
use shapegen::optimize::Control;
use shapegen::optimize::multi::{Member, MultiGa, MultiSnapshot};
use shapegen::optimize::{Optimizer, Settings};
use shapegen::scene::{ObjectiveEvaluator, Scene};

fn main() -> anyhow::Result<()> {
    let seconds: u64 = match std::env::args().nth(1) {
        Some(s) => s
            .parse()
            .context("the argument is the time budget in seconds")?,
        None => 90,
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = root.join("out/building");
    std::fs::create_dir_all(&out)?;

    // The goal: the lot and the scene's objectives, measured on whole populations.
    let scene = Scene::load(root.join("scenes/lot_building.toml"))?;
    let lot = scene.site.lot().context("the scene has a lot")?;
    println!("lot: {} corners, {:.0} m2", lot.len(), lot.area());
    let mut evaluator = ObjectiveEvaluator::new::<LotBuilding>(&scene)?;
    let names: Vec<&str> = evaluator.set().names().collect();
    println!("objectives: {}", names.join(", "));

    // The search: the scene's GA settings and selection, under a time budget.
    let settings = scene.multi_settings().context("a scene with objectives")?;
    let budget = settings
        .ga
        .budget()
        .and_wall_time(Duration::from_secs(seconds));
    let mut ga = MultiGa::<LotBuilding>::new(settings, scene.limits, scene.optimizer.seed)?;
    let mut progress = |s: &MultiSnapshot<'_, LotBuilding>| {
        if s.generation.is_multiple_of(10) {
            let best: Vec<String> = names
                .iter()
                .zip(s.best)
                .map(|(n, v)| format!("{n} {v:.3}"))
                .collect();
            println!(
                "generation {:>2}  {:>3} non-dominated  best {}",
                s.generation,
                s.front.len(),
                best.join(", ")
            );
        }
        Control::Continue
    };
    let result = ga.run(&mut evaluator, &budget, &mut progress)?;
    let elapsed = result.history.last().map_or(0.0, |h| h.elapsed_s);
    println!(
        "{} non-dominated buildings after {} generations, {} evaluations, {elapsed:.1} s",
        result.front.len(),
        result.generations,
        result.evaluations
    );

    // What was found: every building of the front, built on the lot.
    let models: Vec<Vec<Instance>> = result
        .front
        .iter()
        .map(|member| {
            let mut instances = Vec::new();
            member.genome.derive_on(&scene.site, &mut instances);
            instances
        })
        .collect();
    let found = Found {
        out: &out,
        names: &names,
        front: &result.front,
        models: &models,
        meshes: evaluator.meshes(),
        palette: &Palette::new(),
    };
    found.write_front()?;
    found.write_best()?;
    println!(
        "wrote front.csv, contact_sheet.png, front_NNN.glb and best.obj/.mtl/.glb/.png to {}",
        out.display()
    );
    Ok(())
}

/// The front a search found, each member's building derived on the lot, and where its
/// files go.
struct Found<'a> {
    out: &'a Path,
    names: &'a [&'a str],
    front: &'a [Member<LotBuilding>],
    models: &'a [Vec<Instance>],
    meshes: &'a BoundMeshes,
    palette: &'a Palette,
}

impl Found<'_> {
    /// Writes each building of the front as a model and in a table of its objective
    /// values, and a contact sheet of at most 24 of them.
    fn write_front(&self) -> anyhow::Result<()> {
        let mut csv = format!("model,{}\n", self.names.join(","));
        for (i, (member, instances)) in self.front.iter().zip(self.models).enumerate() {
            let model = Model::new(instances, self.meshes, self.palette);
            save_glb(self.out.join(format!("front_{i:03}.glb")), model)?;
            let values: Vec<String> = member.values.iter().map(|v| format!("{v}")).collect();
            csv += &format!("{i},{}\n", values.join(","));
        }
        std::fs::write(self.out.join("front.csv"), csv)?;
        // At most 24 of them, evenly thinned, in the csv's order.
        let step = self.models.len().div_ceil(24).max(1);
        let shown: Vec<&Vec<_>> = self.models.iter().step_by(step).collect();
        ContactSheet {
            cell: 200,
            columns: 8,
        }
        .render(&shown, self.meshes, self.palette, |_, _| {
            Ok::<_, ExportError>(())
        })?
        .save(self.out.join("contact_sheet.png"))?;
        Ok(())
    }

    /// Writes the building whose footprint and front silhouette match best (the largest
    /// mean of the two matches), with a material per part.
    fn write_best(&self) -> anyhow::Result<()> {
        let matches: Vec<usize> = ["top", "front"]
            .iter()
            .filter_map(|n| self.names.iter().position(|m| m == n))
            .collect();
        let score = |values: &[f64]| matches.iter().map(|&k| values[k]).sum::<f64>();
        let best = (0..self.models.len())
            .max_by(|&a, &b| score(&self.front[a].values).total_cmp(&score(&self.front[b].values)))
            .context("the front holds a building")?;
        let instances = &self.models[best];
        let model = Model::new(instances, self.meshes, self.palette);
        save_obj(self.out.join("best"), model)?;
        save_glb(self.out.join("best.glb"), model)?;
        Preview::framing(instances, self.meshes, 800, 600)
            .render(model)?
            .save(self.out.join("best.png"))?;
        let values: Vec<String> = self
            .names
            .iter()
            .zip(&self.front[best].values)
            .map(|(n, v)| format!("{n} {v:.3}"))
            .collect();
        println!("best match: front member {best}, {}", values.join(", "));
        Ok(())
    }
}
