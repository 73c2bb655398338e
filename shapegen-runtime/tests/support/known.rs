//! Known genomes of the test grammars, built by hand.
#![allow(dead_code)]

use glam::{Vec3, vec2, vec3};
use shapegen_runtime::Genome;

use super::city_expanded::{self as city, City};
use super::spaceship_expanded::{Body, Spaceship, Start, Top, TopNext, Wing, WingNext};

pub fn v3(x: f32, y: f32, z: f32) -> Vec3 {
    vec3(x, y, z)
}

pub const BODY_A: Body = Body {
    size: Vec3::new(0.83, 1.2, 0.7),
};
pub const BODY_B: Body = Body { size: Vec3::ONE };
pub const WING_A: Wing = Wing {
    size: Vec3::new(0.5, 0.3, 0.7),
    shift: 0.1,
};
pub const WING_NEXT_A: WingNext = WingNext {
    size: Vec3::new(0.9, 0.95, 1.0),
    shift: -0.25,
};
pub const TOP_A: Top = Top {
    size: Vec3::new(0.5, 0.15, 0.5),
};
pub const TOP_NEXT_A: TopNext = TopNext { size: Vec3::ONE };

/// Start @0 -> body: Body @3 -> wing: Wing @11.
pub fn small() -> Genome<Spaceship> {
    let mut g = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = g.attach(0, "body", BODY_A).unwrap();
    g.attach(body, "wing", WING_A).unwrap();
    g
}

/// Start @0, Body @3, Body @11 (next of @3), Wing @19 (wing of @3), WingNext @26, Top @33
/// (top of @11), TopNext @39. Depth 5.
pub fn ship() -> Genome<Spaceship> {
    let mut g = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let body = g.attach(0, "body", BODY_A).unwrap();
    let next = g.attach(body, "next", BODY_B).unwrap();
    let wing = g.attach(body, "wing", WING_A).unwrap();
    g.attach(wing, "next", WING_NEXT_A).unwrap();
    let top = g.attach(next, "top", TOP_A).unwrap();
    g.attach(top, "next", TOP_NEXT_A).unwrap();
    g
}

pub fn building(height: f32) -> city::Building {
    city::Building {
        footprint: vec2(1.0, 1.5),
        height,
        rotation: std::f32::consts::FRAC_PI_6,
        style: 2,
        floors: -1,
        lit: true,
        block: 3,
    }
}

/// Start @0; lots[3]: Lot @102 -> Building @105 -> roof: Roof @116 -> spire: Roof @120;
/// lots[10]: Lot @124 -> Building @127. Seven genes.
pub fn town() -> Genome<City> {
    let mut g = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = g.attach_at(0, "lots", 3, city::Lot {}).unwrap();
    let b = g.attach(lot, "building", building(4.0)).unwrap();
    let roof = g.attach(b, "roof", city::Roof { pitch: 0.3 }).unwrap();
    g.attach(roof, "spire", city::Roof { pitch: 0.9 }).unwrap();
    let lot = g.attach_at(0, "lots", 10, city::Lot {}).unwrap();
    g.attach(lot, "building", building(7.0)).unwrap();
    g
}
