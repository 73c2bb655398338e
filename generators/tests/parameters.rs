//! Every parameter of every gene of the paper's generators shapes the model: changing
//! any one component of any gene's parameters, within its range, changes the derived
//! instances. The exceptions are the original's own: a range of a single value (the
//! trunk's x and z size) and the city building's floor height, which only detailed
//! facades use.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde_json::Value;
use shapegen_runtime::genome::{Genome, Limits};
use shapegen_runtime::graph::Distribution;
use shapegen_runtime::ops::Operators;
use shapegen_runtime::{Grammar, Instance};

/// The component bounds of a parameter, as `(lo, hi)` per component.
fn bounds(dist: &Distribution) -> Vec<(f32, f32)> {
    match *dist {
        Distribution::Uniform { lo, hi } | Distribution::Angle { lo, hi, .. } => vec![(lo, hi)],
        Distribution::UniformVec2 { lo, hi } => lo.into_iter().zip(hi).collect(),
        Distribution::UniformVec3 { lo, hi } => lo.into_iter().zip(hi).collect(),
        ref other => panic!("the paper's generators have no {other:?} parameters"),
    }
}

fn derive<G: Grammar>(genome: &Genome<G>) -> Vec<Instance> {
    let mut out = Vec::new();
    genome.derive_into(&mut out);
    out
}

/// For random genomes of `G`, changes each parameter component of each gene in turn
/// (through the genome's JSON) and checks the derivation changes; `unused` names the
/// parameters that are known to have no effect. Returns how many changes were checked.
fn every_parameter_matters<G: Grammar>(unused: &[&str]) -> usize {
    let mut ops = Operators::<G>::new(Limits::new(1, 40, 40).unwrap()).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut checked = 0;
    for _ in 0..6 {
        let genome = ops.random(30, &mut rng);
        let before = derive(&genome);
        let json: Value = serde_json::from_str(&genome.to_json()).unwrap();
        for (index, gene) in genome.genes().enumerate() {
            let node = genome.node(gene);
            for param in node.params.iter().filter(|p| !unused.contains(&p.name)) {
                for (component, (lo, hi)) in bounds(&param.dist).into_iter().enumerate() {
                    if lo == hi {
                        continue;
                    }
                    let mut changed = json.clone();
                    let value = &mut changed["genes"][index]["params"][param.name];
                    let slot = match value {
                        Value::Array(items) => &mut items[component],
                        scalar => scalar,
                    };
                    let old = slot.as_f64().unwrap() as f32;
                    let new = if (old - lo).abs() > (hi - old).abs() {
                        lo
                    } else {
                        hi
                    };
                    *slot = Value::from(f64::from(new));
                    let altered = Genome::<G>::from_json(&changed.to_string()).unwrap();
                    assert_ne!(
                        derive(&altered),
                        before,
                        "{}: gene {index} (`{}`), parameter `{}` component {component}: \
                         {old} -> {new} changes nothing",
                        G::GRAPH.name,
                        node.name,
                        param.name
                    );
                    checked += 1;
                }
            }
        }
    }
    checked
}

#[test]
fn every_spaceship_parameter_shapes_the_model() {
    assert!(every_parameter_matters::<generators::Spaceship>(&[]) > 300);
}

#[test]
fn every_tree_parameter_shapes_the_model() {
    assert!(every_parameter_matters::<generators::Tree>(&[]) > 300);
}

#[test]
fn every_city_parameter_but_the_floor_height_shapes_the_model() {
    assert!(every_parameter_matters::<generators::City>(&["floor_height"]) > 100);
}
