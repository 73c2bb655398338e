//! Every program passes naga's WGSL parser and full validation, needing no device; naga
//! refuses a broken source with its message and location, so the checks cannot pass
//! whatever the source.

use shapegen_shaders::{SILHOUETTE, SILHOUETTE_RETAINED, VOLUME, parts};

/// Parses and validates WGSL `source`, or gives naga's message with the source location.
fn validate(source: &str) -> Result<(), String> {
    let module = naga::front::wgsl::parse_str(source).map_err(|err| err.emit_to_string(source))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|err| err.emit_to_string(source))?;
    Ok(())
}

/// Fails with naga's message when `source` does not validate.
fn assert_valid(name: &str, source: &str) {
    if let Err(err) = validate(source) {
        panic!("{name} does not validate:\n{err}");
    }
}

#[test]
fn the_volume_program_validates() {
    assert_valid("VOLUME", VOLUME);
}

#[test]
fn the_silhouette_program_validates() {
    assert_valid("SILHOUETTE", SILHOUETTE);
}

#[test]
fn the_retained_silhouette_program_validates() {
    assert_valid("SILHOUETTE_RETAINED", SILHOUETTE_RETAINED);
}

#[test]
fn the_shared_clip_position_validates_alone() {
    assert_valid("parts::CLIP", parts::CLIP);
}

#[test]
fn a_broken_source_is_refused_with_its_location() {
    let err = validate("@compute @workgroup_size(1) fn main() { let x: u32 = 1.5; }").unwrap_err();
    assert!(err.contains("wgsl:1:"), "{err}");
    let err = validate("fn broken( {").unwrap_err();
    assert!(err.contains("wgsl:1:"), "{err}");
}

#[test]
fn a_silhouette_part_without_clip_position_is_refused() {
    for part in [parts::SILHOUETTE, parts::SILHOUETTE_RETAINED] {
        let err = validate(part).unwrap_err();
        assert!(err.contains("clip_position"), "{err}");
    }
}
