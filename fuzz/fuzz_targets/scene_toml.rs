//! Scene files as `shapegen run SCENE --set KEY=VALUE ..` reads them: the input is the
//! scene's text, then optionally a line `--set` and one override per line. Paths in the
//! scene resolve against the project's `scenes/` folder, so its targets and meshes load.

#![no_main]

use std::path::Path;
use std::sync::LazyLock;

use libfuzzer_sys::fuzz_target;
use shapegen::registry::Registry;
use shapegen::scene::{Overrides, Scene};

static REGISTRY: LazyLock<Registry> = LazyLock::new(Registry::published);

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (scene, sets) = text.split_once("\n--set\n").unwrap_or((text, ""));
    let overrides = Overrides {
        sets: sets.lines().map(str::to_owned).collect(),
        ..Overrides::default()
    };
    // A scene in the project's `scenes/` folder, so that seeded scenes find their targets.
    let folder = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("fuzz/ has a parent");
    let _ = Scene::parse_in(
        scene,
        &folder.join("scenes/fuzz.toml"),
        &REGISTRY,
        &overrides,
    );
});
