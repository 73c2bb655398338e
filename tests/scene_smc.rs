//! Scene files choose the SMC variant: `[optimizer] variant` for smc and sosmc, and
//! `--set optimizer.variant=...`; the paper's settings are the original's.

use std::fs;

use shapegen::optimize::{Order, SmcSettings, SmcVariant};
use shapegen::registry::Registry;
use shapegen::scene::{MethodSettings, Overrides, Scene, SceneError};

fn scene(generator: &str, optimizer: &str, sets: &[&str]) -> Result<Scene, SceneError> {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("cube.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let path = dir.path().join("scene.toml");
    fs::write(
        &path,
        format!(
            "generator = \"{generator}\"\n[limits]\nmin_len = 4\nmax_len = 100\nmax_depth = 15\n\
             [volume]\ngrid = {{ min = [-1, -1, -1], max = [1, 1, 1], resolution = [8, 8, 8] }}\n\
             [[volume.target]]\nmesh = \"cube.obj\"\n[optimizer]\n{optimizer}\n"
        ),
    )
    .unwrap();
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let overrides = Overrides {
        sets,
        ..Overrides::default()
    };
    Scene::open(&path, &Registry::published(), &overrides)
}

fn smc(scene: Result<Scene, SceneError>) -> SmcSettings {
    match scene.unwrap().optimizer.settings {
        MethodSettings::Smc(s) | MethodSettings::Sosmc(s) => s,
        other => panic!("not SMC: {other:?}"),
    }
}

#[test]
fn the_paper_settings_are_the_originals() {
    let cases = [
        ("spaceship", Order::Chromosome, 500, 40),
        ("tree", Order::Stochastic, 1000, 500),
        ("city", Order::Chromosome, 100, 100),
    ];
    for (generator, order, particles, steps) in cases {
        let method = match order {
            Order::Chromosome => "smc",
            Order::Stochastic => "sosmc",
        };
        let s = smc(scene(generator, &format!("method = \"{method}\""), &[]));
        assert_eq!(
            s,
            SmcSettings {
                particles,
                steps,
                order,
                variant: SmcVariant::Original,
                step_back_probability: 0.0,
                max_grows_per_step: 64,
                polish: 0,
                polish_sigma: 0.1,
            },
            "{generator}"
        );
    }
}

#[test]
fn the_variant_is_a_key_and_a_set() {
    let s = smc(scene(
        "spaceship",
        "method = \"sosmc\"\nvariant = \"generative\"",
        &[],
    ));
    assert_eq!(
        (s.variant, s.order),
        (SmcVariant::Generative, Order::Stochastic)
    );
    let s = smc(scene(
        "spaceship",
        "method = \"smc\"\nvariant = \"generative\"",
        &[
            "optimizer.variant=original",
            "optimizer.step_back_probability=0.25",
        ],
    ));
    assert_eq!(
        (s.variant, s.step_back_probability),
        (SmcVariant::Original, 0.25)
    );
    let s = smc(scene(
        "spaceship",
        "method = \"smc\"",
        &["optimizer.variant=generative"],
    ));
    assert_eq!(s.variant, SmcVariant::Generative);
}

#[test]
fn bad_variants_and_step_backs_are_refused_by_name() {
    for bad in ["variant = \"paper\"", "variant = 3"] {
        let err = scene("spaceship", &format!("method = \"smc\"\n{bad}"), &[])
            .unwrap_err()
            .to_string();
        assert!(err.contains("optimizer.variant"), "{err}");
        assert!(err.contains("\"original\" and \"generative\""), "{err}");
    }
    let err = scene(
        "spaceship",
        "method = \"sosmc\"",
        &["optimizer.step_back_probability=2"],
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("optimizer.step_back_probability"), "{err}");
    assert!(err.contains("between 0 and 1"), "{err}");
}
