//! The standard measures of a model against a scene's targets, on the reachable targets'
//! own genomes (which match their targets exactly) and on models that do not.

use std::path::Path;

use generators::{Spaceship, Tree};
use shapegen::scene::{Metrics, Scene, SceneScorer};
use shapegen::{Genome, Grammar, Instance};

/// The scene `NAME.toml` and the genome of its target, `targets/NAME.genome.json`.
fn scene_and_target<G: Grammar>(name: &str) -> (Scene, Genome<G>) {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let scene = Scene::load(scenes.join(format!("{name}.toml"))).unwrap();
    let genome =
        Genome::<G>::load_json(scenes.join(format!("targets/{name}.genome.json"))).unwrap();
    (scene, genome)
}

fn metrics<G: Grammar>(scene: &Scene, instances: &[Instance], genes: usize) -> Metrics {
    let scorer = SceneScorer::new::<G>(scene).unwrap();
    let meshes = scene.meshes.bind(G::GRAPH).unwrap();
    Metrics::of(scene, Some(&scorer), &meshes, genes, instances)
}

#[test]
fn a_volume_targets_own_genome_has_voxel_iou_one_and_a_near_surface() {
    let (scene, genome) = scene_and_target::<Spaceship>("spaceship_fill2");
    let mut instances = Vec::new();
    genome.derive_into(&mut instances);
    let m = metrics::<Spaceship>(&scene, &instances, genome.len());
    assert_eq!(m.voxel_iou, Some(1.0));
    assert_eq!((m.genes, m.instances), (genome.len(), instances.len()));
    assert_eq!(m.triangles, 12 * instances.len()); // boxes
    assert!(m.silhouette_iou.is_empty());
    let surface = m.surface.unwrap();
    // The target's surface is the model's outer surface (voxelized); the model's own
    // boxes also have faces inside the union, which the target lacks.
    assert!(surface.chamfer < 0.2, "{surface:?}");
    assert!(surface.f_score > 0.3, "{surface:?}");
    assert_eq!(surface.samples, shapegen::scene::SURFACE_SAMPLES);

    // Half the model: less of the target, and the same measures again and again.
    let half = &instances[..instances.len() / 2];
    let h = metrics::<Spaceship>(&scene, half, genome.len());
    assert!(h.voxel_iou.unwrap() < 1.0);
    assert!(h.surface.unwrap().f_score < surface.f_score);
    assert_eq!(h, metrics::<Spaceship>(&scene, half, genome.len()));

    // Nothing: IoU 0 and no surface to measure.
    let none = metrics::<Spaceship>(&scene, &[], 1);
    assert_eq!(none.voxel_iou, Some(0.0));
    assert_eq!(none.surface, None);
    assert_eq!(none.triangles, 0);
}

#[test]
fn a_silhouette_targets_own_genome_has_iou_one_per_view() {
    let (scene, genome) = scene_and_target::<Tree>("tree_sketch2");
    let mut instances = Vec::new();
    genome.derive_into(&mut instances);
    let m = metrics::<Tree>(&scene, &instances, genome.len());
    assert_eq!(m.silhouette_iou.len(), 1);
    assert_eq!(m.silhouette_iou[0].target, "targets/tree_sketch2.png");
    assert_eq!(m.silhouette_iou[0].iou, 1.0);
    assert_eq!((m.voxel_iou, m.surface), (None, None));
    let trunk_only = metrics::<Tree>(&scene, &instances[..1], genome.len());
    assert!(trunk_only.silhouette_iou[0].iou < 0.5);
}

#[test]
fn a_scan_is_nearer_to_its_own_model_than_to_others_and_measured_per_cloud() {
    use rand::SeedableRng;
    use shapegen::score::objective::{Objective, Surface};

    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let scene = Scene::load(scenes.join("spaceship_scan.toml")).unwrap();
    let genome: Genome<Spaceship> =
        Genome::load_json(scenes.join("targets/spaceship_fill2.genome.json")).unwrap();
    let goal = scene.objectives.as_ref().unwrap();
    let [(name, Objective::Chamfer(chamfer))] = goal.set.entries() else {
        panic!("{:?}", goal.set.entries());
    };
    assert_eq!(
        (name.as_str(), chamfer.cloud().points.len()),
        ("scan", 4096)
    );
    let meshes = scene.meshes.bind(Spaceship::GRAPH).unwrap();
    let chamfer_of = |g: &Genome<Spaceship>| {
        let mut instances = Vec::new();
        g.derive_into(&mut instances);
        chamfer.measure(&Surface::from_instances(&instances, &meshes))
    };
    let own = chamfer_of(&genome);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    let mut ops = shapegen::ops::Operators::<Spaceship>::new(scene.limits).unwrap();
    for _ in 0..50 {
        let other = ops.random(40, &mut rng);
        assert!(
            own < chamfer_of(&other),
            "{own} against {}",
            chamfer_of(&other)
        );
    }
    // The run's measures: against the whole cloud, at 1 % of its diagonal.
    let mut instances = Vec::new();
    genome.derive_into(&mut instances);
    let m = Metrics::of(&scene, None, &meshes, genome.len(), &instances);
    assert_eq!((m.voxel_iou, m.surface), (None, None));
    let [cloud] = &m.point_clouds[..] else {
        panic!("{:?}", m.point_clouds);
    };
    assert_eq!(cloud.objective, "scan");
    // Inner faces of the model's boxes are far from the scan; its outer faces are on it.
    assert!(cloud.distance.chamfer < 0.2, "{cloud:?}");
    assert!(cloud.distance.f_score > 0.2, "{cloud:?}");
}
