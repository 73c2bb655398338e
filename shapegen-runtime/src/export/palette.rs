//! Colours of the exported meshes.

use std::collections::BTreeMap;

use crate::geometry::MeshId;

/// Default colours by mesh name (linear RGB; sRGB hex in the comments).
const NAMED: [(&str, [f32; 3]); 8] = [
    ("cube", [0.2542, 0.3278, 0.4341]),   // #8A9BB0 grey-blue
    ("trunk", [0.1946, 0.0844, 0.0296]),  // #7A5230 brown
    ("leaf", [0.0782, 0.3231, 0.0423]),   // #4F9A3A green
    ("wall", [0.7682, 0.6654, 0.5149]),   // #E3D5BE sandstone
    ("roof", [0.3419, 0.0685, 0.0423]),   // #9E4A3A tile red
    ("window", [0.0482, 0.1070, 0.1946]), // #3E5C7A glass blue
    ("door", [0.1470, 0.0685, 0.0273]),   // #6B4A2E wood
    ("slab", [0.3231, 0.3231, 0.3231]),   // #9A9A9A concrete
];

/// Default colours for other meshes, chosen by mesh id.
const CYCLE: [[f32; 3]; 8] = [
    [0.6308, 0.2623, 0.0685], // #D08C4A amber
    [0.1070, 0.2747, 0.5841], // #5C8FC9 blue
    [0.4793, 0.1070, 0.1070], // #B85C5C brick
    [0.2623, 0.1470, 0.4397], // #8C6BB1 purple
    [0.0704, 0.3663, 0.3515], // #4BA3A0 teal
    [0.5841, 0.4341, 0.0782], // #C9B04F mustard
    [0.6308, 0.2122, 0.3763], // #D07FA5 pink
    [0.2122, 0.2623, 0.1022], // #7F8C5A olive
];

/// The colour of each mesh in an export: linear RGB components in `[0, 1]`, written as
/// glTF `baseColorFactor` (with alpha 1) and MTL `Kd`.
///
/// By default `cube` is grey-blue, `trunk` brown and `leaf` green, and a building's
/// parts `wall` sandstone, `roof` tile red, `window` glass blue, `door` wood and `slab`
/// concrete; other meshes take distinct colours by mesh id. [`set`](Self::set) overrides a mesh's colour by name.
///
/// ```
/// use shapegen_runtime::{CUBE, MeshId, export::Palette};
///
/// let palette = Palette::new().with("window", [0.1, 0.2, 0.4]);
/// assert_eq!(palette.color(MeshId(3), "window"), [0.1, 0.2, 0.4]);
/// assert_ne!(palette.color(CUBE, "cube"), palette.color(MeshId(1), "roof"));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Palette {
    overrides: BTreeMap<String, [f32; 3]>,
}

impl Palette {
    /// The default palette.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the colour of the mesh called `name`.
    pub fn set(&mut self, name: impl Into<String>, rgb: [f32; 3]) -> &mut Self {
        self.overrides.insert(name.into(), rgb);
        self
    }

    /// The palette with the colour of the mesh called `name` set.
    pub fn with(mut self, name: impl Into<String>, rgb: [f32; 3]) -> Self {
        self.set(name, rgb);
        self
    }

    /// The colour of mesh `id`, called `name`: its override if any, else its default.
    pub fn color(&self, id: MeshId, name: &str) -> [f32; 3] {
        if let Some(&rgb) = self.overrides.get(name) {
            return rgb;
        }
        match NAMED.iter().find(|(n, _)| *n == name) {
            Some(&(_, rgb)) => rgb,
            None => CYCLE[id.0 as usize % CYCLE.len()],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_by_name_then_by_id() {
        let p = Palette::new();
        assert_eq!(p.color(MeshId(0), "cube"), NAMED[0].1);
        assert_eq!(p.color(MeshId(1), "trunk"), NAMED[1].1);
        assert_eq!(p.color(MeshId(2), "leaf"), NAMED[2].1);
        let others: Vec<_> = (1..9).map(|i| p.color(MeshId(i), "part")).collect();
        for (i, a) in others.iter().enumerate() {
            assert!(others[i + 1..].iter().all(|b| a != b), "distinct");
            assert!(NAMED.iter().all(|(_, n)| a != n));
        }
        let q = p.with("leaf", [1.0, 0.0, 0.0]);
        assert_eq!(q.color(MeshId(2), "leaf"), [1.0, 0.0, 0.0]);
    }
}
