//! The silhouette scorer against the published scenes.

use std::path::{Path, PathBuf};

use generators::{city, spaceship, tree};
use glam::{Vec2, vec2, vec3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::score::silhouette::{
    Camera, GpuSilhouetteScorer, ImageTarget, OrbitCamera, SilhouetteCounts, SilhouetteScorer,
};
use shapegen_runtime::score::{Form, InstanceBatch, Scorer, count_batch};
use shapegen_runtime::{Genome, Grammar, Instance, Limits, Operators};

const SMOOTH: Form = Form::Smooth {
    good: 1.0,
    bad: 1.0,
};

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/paper-scenes")
}

fn city_camera() -> Camera {
    Camera::Orbit(OrbitCamera {
        phi: -3.05161,
        theta: 0.0479887,
        radius: 12.4346,
        lookat: vec3(1.82669, 4.65407, -0.620025),
        fov_degrees: 60.0,
        near: 0.1,
        far: 100.0,
    })
}

fn tree_camera() -> Camera {
    Camera::Orbit(OrbitCamera {
        // The published value, -1.5708 (about -pi/2).
        #[allow(clippy::approx_constant)]
        phi: -1.5708,
        theta: 0.0,
        radius: 9.4716,
        lookat: vec3(-0.680994, 3.2558, 0.0),
        fov_degrees: 60.0,
        near: 0.1,
        far: 100.0,
    })
}

fn load(scene: &str, file: &str, camera: Camera) -> ImageTarget {
    let path = scenes().join(scene).join(file);
    let image = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    ImageTarget::from_mask(file.to_owned(), &image, camera, 1.0, -1.0).unwrap()
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

fn population<G: Grammar>(limits: Limits, initial_len: u32, n: usize, seed: u64) -> InstanceBatch {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut ops = Operators::<G>::new(limits).unwrap();
    let mut batch = InstanceBatch::new();
    for _ in 0..n {
        batch.push_genome(&ops.random(initial_len, &mut rng));
    }
    batch
}

#[test]
fn counts_do_not_depend_on_the_thread_count() {
    let scorer = city_scorer();
    let batch = population::<city::City>(city::PAPER_LIMITS, 50, 24, 3);
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
    let batch = population::<tree::Tree>(tree::PAPER_LIMITS, 100, 8, 5);
    let mut out = vec![SilhouetteCounts::default(); batch.len()];
    count_batch(&scorer, &batch, &mut out);
    for c in &out {
        let t = c.targets()[0];
        assert!(t.covered > 0 && t.covered == t.on_target + t.off_target);
        let f = scorer.fitness(c);
        assert!((-1.0..=1.0).contains(&f), "{f}");
    }
}

// --- GPU against CPU ----------------------------------------------------------------

/// The GPU's counts agree with the CPU's up to pixels whose centres lie within rounding
/// of an edge: at most 0.5% of the CPU's count plus 2 pixels per instance.
fn assert_close(what: &str, cpu: u64, gpu: u64, instances: usize) {
    let tolerance = cpu as f64 * 0.005 + 2.0 * instances as f64;
    assert!(
        (cpu as f64 - gpu as f64).abs() <= tolerance,
        "{what}: cpu {cpu}, gpu {gpu}, tolerance {tolerance}"
    );
}

fn small(scene: &str, file: &str, camera: Camera, weight_map: bool) -> ImageTarget {
    let path = scenes().join(scene).join(file);
    let image =
        image::open(&path)
            .unwrap()
            .resize_exact(160, 120, image::imageops::FilterType::Triangle);
    if weight_map {
        ImageTarget::from_weight_map(file.to_owned(), &image, camera, 1.0, -0.5).unwrap()
    } else {
        ImageTarget::from_mask(file.to_owned(), &image, camera, 1.0, -1.0).unwrap()
    }
}

fn compare_on_gpu(scorer: &SilhouetteScorer, batch: &InstanceBatch) {
    let Some(gpu) = shapegen_runtime::gpu::test_context() else {
        return;
    };
    let on_gpu = GpuSilhouetteScorer::new(gpu, scorer).unwrap();
    let mut cpu = vec![SilhouetteCounts::default(); batch.len()];
    count_batch(scorer, batch, &mut cpu);
    let mut out = vec![SilhouetteCounts::default(); batch.len()];
    on_gpu.count_batch(batch, &mut out).unwrap();
    let (mut exact, mut worst) = (0, 0);
    for (i, (c, g)) in cpu.iter().zip(&out).enumerate() {
        let n = batch.model(i).len();
        for (tc, tg) in c.targets().iter().zip(g.targets()) {
            let what = format!("model {i} ({n} instances)");
            assert_close(
                &format!("{what} covered"),
                tc.covered.into(),
                tg.covered.into(),
                n,
            );
            assert_close(
                &format!("{what} on"),
                tc.on_target.into(),
                tg.on_target.into(),
                n,
            );
            assert_close(
                &format!("{what} off"),
                tc.off_target.into(),
                tg.off_target.into(),
                n,
            );
            assert_close(
                &format!("{what} levels"),
                tc.level_sum / 255,
                tg.level_sum / 255,
                n + 1,
            );
            assert_eq!(tg.covered, tg.on_target + tg.off_target);
            worst = worst.max(tc.covered.abs_diff(tg.covered));
        }
        exact += usize::from(c == g);
    }
    eprintln!(
        "{exact} of {} models counted identically; covered pixels differ by at most {worst}",
        batch.len()
    );
    assert!(cpu.iter().any(|c| c.targets()[0].covered > 0));
    // The same batch again gives the same counts: bitsets are cleared between calls.
    let mut again = vec![SilhouetteCounts::default(); batch.len()];
    on_gpu.count_batch(batch, &mut again).unwrap();
    assert_eq!(out, again);
}

#[test]
fn gpu_matches_cpu_on_random_cities() {
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    let targets = vec![
        small("city_whale", "city_target_whale.png", city_camera(), false),
        small("city_whale", "city_target_whale.png", tree_camera(), true),
    ];
    let scorer = SilhouetteScorer::new(targets, &meshes, SMOOTH).unwrap();
    compare_on_gpu(
        &scorer,
        &population::<city::City>(city::PAPER_LIMITS, 50, 40, 21),
    );
}

#[test]
fn gpu_matches_cpu_on_random_trees() {
    let meshes = generators::default_meshes()
        .bind(tree::Tree::GRAPH)
        .unwrap();
    let targets = vec![small(
        "tree_sketch1",
        "tree_target_sketch1.png",
        tree_camera(),
        false,
    )];
    let scorer = SilhouetteScorer::new(targets, &meshes, SMOOTH).unwrap();
    compare_on_gpu(
        &scorer,
        &population::<tree::Tree>(tree::PAPER_LIMITS, 150, 30, 22),
    );
}

#[test]
fn gpu_matches_cpu_on_random_spaceships_through_a_close_camera() {
    // Close enough that some hulls reach behind the near plane.
    let camera = Camera::Orbit(OrbitCamera {
        phi: 0.7,
        theta: 0.35,
        radius: 6.0,
        lookat: vec3(0.0, 0.4, 4.0),
        fov_degrees: 70.0,
        near: 0.5,
        far: 50.0,
    });
    let meshes = generators::default_meshes()
        .bind(spaceship::Spaceship::GRAPH)
        .unwrap();
    let targets = vec![small(
        "tree_sketch1",
        "tree_target_sketch1.png",
        camera,
        true,
    )];
    let scorer = SilhouetteScorer::new(targets, &meshes, SMOOTH).unwrap();
    compare_on_gpu(
        &scorer,
        &population::<spaceship::Spaceship>(spaceship::PAPER_LIMITS, 50, 40, 23),
    );
}

#[test]
fn gpu_counts_a_batch_larger_than_one_chunk() {
    let Some(gpu) = shapegen_runtime::gpu::test_context() else {
        return;
    };
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    // 4096 x 4096 pixels: 2 MiB of bitset per model, so 64 models per 128 MiB binding.
    let camera = city_camera();
    let image = image::DynamicImage::ImageLuma8(image::GrayImage::from_fn(4096, 4096, |x, _| {
        image::Luma([(x / 16) as u8])
    }));
    let target = ImageTarget::from_weight_map("big".into(), &image, camera, 1.0, -1.0).unwrap();
    let scorer = SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap();
    let on_gpu = GpuSilhouetteScorer::new(gpu, &scorer).unwrap();
    assert_eq!(on_gpu.bitset_bytes(), 2 << 20);
    let batch = population::<city::City>(city::PAPER_LIMITS, 20, on_gpu.chunk_size() + 3, 24);
    let mut cpu = vec![SilhouetteCounts::default(); batch.len()];
    count_batch(&scorer, &batch, &mut cpu);
    let mut out = vec![SilhouetteCounts::default(); batch.len()];
    on_gpu.count_batch(&batch, &mut out).unwrap();
    for (i, (c, g)) in cpu.iter().zip(&out).enumerate() {
        let n = batch.model(i).len();
        assert_close(
            &format!("model {i}"),
            c.targets()[0].covered.into(),
            g.targets()[0].covered.into(),
            4 * n,
        );
    }
    let err = on_gpu.count_batch(&batch, &mut out[1..]).unwrap_err();
    assert!(err.to_string().contains("give one per model"), "{err}");
}
