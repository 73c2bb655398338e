//! The WGSL shaders of shapegen's GPU scorers, each program as the source text the
//! runtime compiles.
//!
//! | constant | program | compiled by |
//! |---|---|---|
//! | [`VOLUME`] | `volume.wgsl`: the compute shader counting the voxels of box instances (and of the runs the CPU rasterises) | `score::volume::GpuVolumeScorer` |
//! | [`SILHOUETTE`] | `clip.wgsl` then `silhouette.wgsl`: instanced draws into per-model coverage bitsets | `score::silhouette::GpuSilhouetteScorer` |
//! | [`SILHOUETTE_RETAINED`] | `clip.wgsl` then `silhouette_retained.wgsl`: instanced draws into per-pixel fragment counts kept between generations | `score::silhouette::GpuRetention` |
//!
//! The runtime (`shapegen-runtime`) hands each constant to `gpu::GpuContext::shader`,
//! which creates a `wgpu` shader module from the WGSL text; the Rust structs the shaders
//! read are `#[repr(C)]` there, with their sizes asserted at compile time. Both
//! silhouette programs start with the same [`parts::CLIP`], whose `clip_position` places
//! every vertex, so both draw the same fragments. This crate's tests check every program
//! with naga (parsing and full validation), needing no device.
//!
//! ```
//! use shapegen_shaders::{SILHOUETTE, SILHOUETTE_RETAINED, VOLUME, parts};
//!
//! // Each silhouette program is `clip.wgsl` followed by its own file.
//! assert_eq!(SILHOUETTE, [parts::CLIP, parts::SILHOUETTE].concat());
//! assert_eq!(SILHOUETTE_RETAINED, [parts::CLIP, parts::SILHOUETTE_RETAINED].concat());
//! assert!(SILHOUETTE.contains("fn clip_position("));
//!
//! // The volume program is one file, with one compute entry point.
//! assert!(VOLUME.contains("@compute @workgroup_size(64)"));
//! ```

pub mod parts;

/// The volume scorer's compute program (`volume.wgsl`): one invocation per (box instance,
/// voxel row) marks the row's voxels in its model's coverage bitset and adds to the
/// model's class and overlap counters, with the same integer formulas as the CPU path.
pub const VOLUME: &str = include_str!("../volume.wgsl");

/// The silhouette scorer's render program: [`parts::CLIP`] followed by
/// [`parts::SILHOUETTE`] (`clip.wgsl` then `silhouette.wgsl`). Its fragment stage sets
/// each covered pixel's bit in a per-(target, model) bitset and counts it once.
pub const SILHOUETTE: &str = concat!(
    include_str!("../clip.wgsl"),
    include_str!("../silhouette.wgsl")
);

/// The retained silhouette program: [`parts::CLIP`] followed by
/// [`parts::SILHOUETTE_RETAINED`] (`clip.wgsl` then `silhouette_retained.wgsl`). Its
/// fragment stage adds to or subtracts from a model's per-pixel fragment counts, so that a
/// bred child is counted by drawing only the instances that differ from its parent's.
pub const SILHOUETTE_RETAINED: &str = concat!(
    include_str!("../clip.wgsl"),
    include_str!("../silhouette_retained.wgsl")
);
