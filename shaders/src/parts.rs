//! The files the silhouette programs are made of, each as written. Only [`CLIP`] is valid
//! WGSL on its own; the others call its `clip_position` and are compiled after it, as
//! [`SILHOUETTE`](crate::SILHOUETTE) and
//! [`SILHOUETTE_RETAINED`](crate::SILHOUETTE_RETAINED).

/// `clip.wgsl`: `clip_position`, a mesh vertex moved by its instance's affine transform and
/// projected through the camera, with the near plane at depth 0 and the far clip out of the
/// way. Shared by both silhouette programs, so that they draw the same fragments.
pub const CLIP: &str = include_str!("../clip.wgsl");

/// `silhouette.wgsl`: the silhouette scorer's vertex and fragment stages, without
/// [`CLIP`].
pub const SILHOUETTE: &str = include_str!("../silhouette.wgsl");

/// `silhouette_retained.wgsl`: the retained silhouette program's vertex and fragment
/// stages, without [`CLIP`].
pub const SILHOUETTE_RETAINED: &str = include_str!("../silhouette_retained.wgsl");
