//! Every parameter type with every distribution it takes, and the constants they hold.
#![deny(warnings, unused_qualifications)]

use shapegen::graph::{AngleUnit, Distribution};
use shapegen::prelude::*;

generator! {
    Kinds {
        axiom Every;
        node Every {
            params {
                uniform: f32 ~ uniform(-1.0, 2 * 1.5),
                constant: f32 ~ uniform(0.5, 0.5),
                third: f32 ~ uniform(0.0, 1.0 / 3.0),
                degrees: f32 ~ degrees(-90, 180),
                radians: f32 ~ radians(-FRAC_PI_2, std::f32::consts::PI),
                pair: Vec2 ~ uniform([0.0, -1.0], [1.0; 2]),
                triple: Vec3 ~ uniform([0.25; 3], [0.5, 1.0, core::f32::consts::TAU]),
                count: i32 ~ uniform(-3..=3),
                open: i32 ~ uniform(-3..3),
                index: u32 ~ uniform(1..=4),
                choice: u32 ~ weighted([0.0, 2.0, 1.0]),
                flag: bool ~ bernoulli(0.25),
            }
            derive(s) {
                let _: (f32, f32, f32, f32, f32) = (uniform, constant, third, degrees, radians);
                let _: (Vec2, Vec3) = (pair, triple);
                let _: (i32, i32, u32, u32, bool) = (count, open, index, choice, flag);
                s.emit(CUBE);
            }
        }
    }
}

fn main() {
    let node = &Kinds::GRAPH.nodes[0];
    let dists: Vec<Distribution> = node.params.iter().map(|p| p.dist).collect();
    let pi = std::f32::consts::PI;
    assert_eq!(
        dists,
        [
            Distribution::Uniform { lo: -1.0, hi: 3.0 },
            Distribution::Uniform { lo: 0.5, hi: 0.5 },
            Distribution::Uniform { lo: 0.0, hi: 1.0 / 3.0 },
            Distribution::Angle { lo: -pi / 2.0, hi: pi, unit: AngleUnit::Degrees },
            Distribution::Angle { lo: -pi / 2.0, hi: pi, unit: AngleUnit::Radians },
            Distribution::UniformVec2 { lo: [0.0, -1.0], hi: [1.0, 1.0] },
            Distribution::UniformVec3 { lo: [0.25; 3], hi: [0.5, 1.0, 2.0 * pi] },
            Distribution::Int { lo: -3, hi: 3 },
            Distribution::Int { lo: -3, hi: 2 },
            Distribution::Index { lo: 1, hi: 4 },
            Distribution::Weighted { weights: &[0.0, 2.0, 1.0] },
            Distribution::Bernoulli { p: 0.25 },
        ]
    );
    let offsets: Vec<u32> = node.params.iter().map(|p| p.offset).collect();
    assert_eq!(offsets, [0, 1, 2, 3, 4, 5, 7, 10, 11, 12, 13, 14]);
    assert_eq!(node.param_words, 15);
    assert_eq!(<Every as shapegen::NodeParams>::WORDS, 15);
    // Values round-trip through gene words.
    let value = Every {
        uniform: 1.0,
        constant: 0.5,
        third: 0.25,
        degrees: 1.0,
        radians: -1.0,
        pair: vec2(0.5, 0.0),
        triple: vec3(0.3, 0.6, 1.0),
        count: -2,
        open: 2,
        index: 3,
        choice: 2,
        flag: true,
    };
    let mut words = [0u32; 15];
    shapegen::NodeParams::write(&value, &mut words);
    assert_eq!(<Every as shapegen::NodeParams>::read(&words), value);
}
