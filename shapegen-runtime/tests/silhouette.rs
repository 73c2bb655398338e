//! The silhouette scorer against the published scenes.

mod support {
    pub mod scenes;
    pub mod silhouette_scenes;
}

use generators::{city, tree};
use glam::{Vec2, vec2, vec3};
use shapegen_runtime::score::silhouette::{
    Camera, ImageTarget, SilhouetteCounts, SilhouetteScorer, Weighting,
};
use shapegen_runtime::score::{Scorer, count_batch};
use shapegen_runtime::{Genome, Grammar, Instance};
use support::scenes::{population, scenes};
use support::silhouette_scenes::{SMOOTH, city_camera, tree_camera};

fn load(scene: &str, file: &str, camera: Camera) -> ImageTarget {
    let path = scenes().join(scene).join(file);
    let image = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    ImageTarget::new(file.to_owned(), &image, camera, Weighting::mask(1.0, -1.0)).unwrap()
}

fn derive<G: Grammar>(g: &Genome<G>) -> Vec<Instance> {
    let mut out = Vec::new();
    g.derive_append(&mut out);
    out
}

fn full_city(footprint: Vec2, height: f32) -> Vec<Instance> {
    let mut g = Genome::<city::City>::with_root(city::Start {}).unwrap();
    for k in 0..100 {
        let lot = g.attach_at(0, "lots", k, city::Lot {}).unwrap();
        g.attach(
            lot,
            "building",
            city::Building {
                footprint,
                height,
                floor_height: 0.3,
                rotation: 0.0,
            },
        )
        .unwrap();
    }
    derive(&g)
}

fn trunk_alone() -> Vec<Instance> {
    let mut g = Genome::<tree::Tree>::with_root(tree::Start {}).unwrap();
    g.attach(
        0,
        "trunk",
        tree::Trunk {
            size: vec3(0.8, 1.8, 0.8),
        },
    )
    .unwrap();
    derive(&g)
}

/// Target and coverage side by side, one character per 10 x 20 pixel block:
/// `#` both, `t` target only, `m` model only.
fn picture(target: &ImageTarget, mask: &[bool]) -> String {
    let (w, h) = (target.width(), target.height());
    let mut s = String::new();
    for by in (0..h).step_by(20) {
        for bx in (0..w).step_by(10) {
            let (mut t, mut m) = (false, false);
            for y in by..(by + 20).min(h) {
                for x in bx..(bx + 10).min(w) {
                    t |= target.is_target(x, y);
                    m |= mask[(y * w + x) as usize];
                }
            }
            s.push(match (t, m) {
                (true, true) => '#',
                (true, false) => 't',
                (false, true) => 'm',
                _ => '.',
            });
        }
        s.push('\n');
    }
    s
}

fn city_scorer() -> SilhouetteScorer {
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    let target = load("city_whale", "city_target_whale.png", city_camera());
    SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap()
}

fn tree_scorer() -> SilhouetteScorer {
    let meshes = generators::default_meshes()
        .bind(tree::Tree::GRAPH)
        .unwrap();
    let target = load("tree_sketch1", "tree_target_sketch1.png", tree_camera());
    SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap()
}

fn mask_of(scorer: &SilhouetteScorer, model: &[Instance]) -> Vec<bool> {
    let t = &scorer.targets()[0];
    let mut mask = vec![false; (t.width() * t.height()) as usize];
    scorer.coverage_mask(0, model, &mut mask).unwrap();
    mask
}

#[test]
fn a_full_city_of_tall_buildings_covers_the_whale() {
    let scorer = city_scorer();
    let model = full_city(vec2(1.98, 1.98), 10.0);
    let counts = scorer.count(&model, &mut scorer.scratch()).targets()[0];
    let target = &scorer.targets()[0];
    let total = target.target_pixels();
    assert!(total > 100_000, "the whale has {total} black pixels");
    let picture = picture(target, &mask_of(&scorer, &model));
    assert!(
        f64::from(counts.on_target) >= 0.995 * total as f64,
        "{} of {total} whale pixels covered\n{picture}",
        counts.on_target
    );
    assert_eq!(counts.covered, counts.on_target + counts.off_target);
}

#[test]
fn low_buildings_stay_below_the_whale_s_back() {
    let scorer = city_scorer();
    let model = full_city(vec2(0.5, 0.5), 3.0);
    let mask = mask_of(&scorer, &model);
    let target = &scorer.targets()[0];
    // The topmost covered row of low buildings lies below the whale's topmost row.
    let top = |f: &dyn Fn(u32, u32) -> bool| (0..600).find(|&y| (0..800).any(|x| f(x, y)));
    let model_top = top(&|x, y| mask[(y * 800 + x) as usize]).unwrap();
    let whale_top = top(&|x, y| target.is_target(x, y)).unwrap();
    assert!(
        model_top > whale_top + 100,
        "{model_top} vs {whale_top}\n{}",
        picture(target, &mask)
    );
}

#[test]
fn a_lone_trunk_stands_on_the_sketch_s_trunk() {
    let scorer = tree_scorer();
    let model = trunk_alone();
    let mask = mask_of(&scorer, &model);
    let target = &scorer.targets()[0];
    let picture = picture(target, &mask);
    let counts = scorer.count(&model, &mut scorer.scratch()).targets()[0];
    assert!(counts.covered > 1000, "{picture}");
    assert!(
        f64::from(counts.on_target) >= 0.75 * f64::from(counts.covered),
        "{} of {} trunk pixels on the sketch\n{picture}",
        counts.on_target,
        counts.covered
    );
    // In the rows the trunk covers, its centre and the sketch's coincide; a mirrored
    // image would put them 70 pixels apart.
    let rows: Vec<u32> = (0..600)
        .filter(|&y| (0..800).any(|x| mask[(y * 800 + x) as usize]))
        .collect();
    let mean = |f: &dyn Fn(u32, u32) -> bool| {
        let xs: Vec<u32> = rows
            .iter()
            .flat_map(|&y| (0..800).filter(move |&x| f(x, y)))
            .collect();
        xs.iter().map(|&x| f64::from(x)).sum::<f64>() / xs.len() as f64
    };
    let model_x = mean(&|x, y| mask[(y * 800 + x) as usize]);
    let sketch_x = mean(&|x, y| target.is_target(x, y));
    assert!(
        (model_x - sketch_x).abs() < 8.0,
        "{model_x} vs {sketch_x}\n{picture}"
    );
    // The trunk stands in the lower part of the picture, its foot near the sketch's.
    assert!(rows[0] > 380 && *rows.last().unwrap() > 500, "{picture}");
}

#[test]
fn counts_do_not_depend_on_the_thread_count() {
    let scorer = city_scorer();
    let batch = population::<city::City>(24, city::PAPER_LIMITS, 50, 3);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out = vec![SilhouetteCounts::default(); batch.len()];
        pool.install(|| count_batch(&scorer, &batch, &mut out));
        out
    };
    let one = run(1);
    assert!(one.iter().any(|c| c.targets()[0].covered > 0));
    // Each model counted alone, with a fresh scratch, gives the same.
    for (i, c) in one.iter().enumerate() {
        assert_eq!(*c, scorer.count(batch.model(i), &mut scorer.scratch()));
    }
    assert_eq!(one, run(3));
    assert_eq!(one, run(8));
}

#[test]
fn random_trees_score_between_the_bounds() {
    let scorer = tree_scorer();
    let batch = population::<tree::Tree>(8, tree::PAPER_LIMITS, 100, 5);
    let mut out = vec![SilhouetteCounts::default(); batch.len()];
    count_batch(&scorer, &batch, &mut out);
    for c in &out {
        let t = c.targets()[0];
        assert!(t.covered > 0 && t.covered == t.on_target + t.off_target);
        let f = scorer.fitness(c);
        assert!((-1.0..=1.0).contains(&f), "{f}");
    }
}

#[test]
fn the_iou_form_is_good_times_the_silhouette_iou_runs_report() {
    use shapegen_runtime::score::Form;
    use shapegen_runtime::score::metrics::silhouette_iou;
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    let target = load("city_whale", "city_target_whale.png", city_camera());
    let scorer = SilhouetteScorer::new(vec![target], &meshes, Form::Iou { good: 2.0 }).unwrap();
    let batch = population::<city::City>(40, city::PAPER_LIMITS, 50, 11);
    let mut counts = vec![SilhouetteCounts::default(); batch.len()];
    count_batch(&scorer, &batch, &mut counts);
    let mut positive = 0;
    for c in &counts {
        let iou = silhouette_iou(&scorer.targets()[0], &c.targets()[0]);
        assert_eq!(scorer.fitness(c), 2.0 * iou);
        assert!((0.0..=1.0).contains(&iou));
        positive += usize::from(iou > 0.0);
    }
    assert!(positive > 30, "{positive} of 40 cities overlap the whale");
    // A city covering the whole whale and more: below 2, above 0.
    let full = full_city(vec2(1.98, 1.98), 10.0);
    let f = scorer.fitness(&scorer.count(&full, &mut scorer.scratch()));
    assert!(f > 0.0 && f < 2.0, "{f}");
}
