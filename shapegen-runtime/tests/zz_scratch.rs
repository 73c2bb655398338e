use shapegen_runtime::Grammar;
use shapegen_runtime::genome::GenomeSet;
use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, Surface};
#[test]
fn stats() {
    let set = GenomeSet::<generators::building::Building>::load("/tmp/front_before.genomes.json")
        .unwrap();
    let meshes = generators::default_meshes()
        .bind(generators::building::Building::GRAPH)
        .unwrap();
    let mut inst = Vec::new();
    let mut scratch = ObjectiveScratch::default();
    let surfaces: Vec<Surface> = set
        .genomes
        .iter()
        .map(|g| {
            g.derive_into(&mut inst);
            Surface::from_instances(&inst, &meshes)
        })
        .collect();
    let t0 = std::time::Instant::now();
    for g in set.genomes.iter() {
        g.derive_into(&mut inst);
        let _ = Surface::from_instances(&inst, &meshes);
    }
    println!("surfaces {:?}", t0.elapsed());
    for o in [
        Objective::UniqueNormals { tolerance_deg: 1.0 },
        Objective::NormalSpread { tolerance_deg: 1.0 },
        Objective::NormalSpread { tolerance_deg: 5.0 },
    ] {
        let t0 = std::time::Instant::now();
        let mut tr = 0.0;
        for s in &surfaces {
            tr += o.measure(s, &mut scratch);
        }
        println!("{o:?} {} in {:?}", tr, t0.elapsed());
    }
}
