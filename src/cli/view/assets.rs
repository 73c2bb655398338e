//! The viewer's page and the libraries it runs, embedded in the binary: nothing is
//! fetched from the network. The libraries are the npm registry's packages, vendored
//! gzipped by `scripts/vendor-viewer.sh` into `assets/viewer/vendor/` with their licences.

use std::io::Read;

use flate2::read::GzDecoder;

/// One embedded file.
#[derive(Debug, Clone, Copy)]
pub struct Asset {
    /// Its path under `/assets/` (and under `assets/viewer/`, without `.gz`).
    pub name: &'static str,
    /// Its MIME type.
    pub mime: &'static str,
    /// Its bytes as stored: gzipped when `gzipped`.
    pub bytes: &'static [u8],
    /// Whether `bytes` are gzipped.
    pub gzipped: bool,
}

impl Asset {
    /// The file's own bytes, unpacked if stored gzipped.
    ///
    /// # Errors
    /// When the stored bytes do not unpack (a corrupt build).
    pub fn unpacked(&self) -> std::io::Result<Vec<u8>> {
        if !self.gzipped {
            return Ok(self.bytes.to_vec());
        }
        let mut out = Vec::with_capacity(self.bytes.len() * 4);
        GzDecoder::new(self.bytes).read_to_end(&mut out)?;
        Ok(out)
    }

    /// The file's text, unpacked.
    ///
    /// # Errors
    /// When it does not unpack or is not UTF-8.
    pub fn text(&self) -> std::io::Result<String> {
        String::from_utf8(self.unpacked()?)
            .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e))
    }
}

/// Declares [`ASSETS`]: name, MIME type, and whether the file is stored gzipped.
macro_rules! assets {
    ($($name:literal, $mime:literal, $gz:tt;)*) => {
        /// Every embedded file, by name.
        pub const ASSETS: &[Asset] = &[
            $(Asset {
                name: $name,
                mime: $mime,
                bytes: assets!(@bytes $name, $gz),
                gzipped: $gz,
            },)*
        ];
    };
    (@bytes $name:literal, true) => {
        include_bytes!(concat!("../../../assets/viewer/", $name, ".gz"))
    };
    (@bytes $name:literal, false) => {
        include_bytes!(concat!("../../../assets/viewer/", $name))
    };
}

assets! {
    "index.html", "text/html; charset=utf-8", false;
    "viewer.js", "text/javascript; charset=utf-8", false;
    "viewer.css", "text/css; charset=utf-8", false;
    "vendor/three/three.module.js", "text/javascript; charset=utf-8", true;
    "vendor/three/three.core.js", "text/javascript; charset=utf-8", true;
    "vendor/three/addons/loaders/GLTFLoader.js", "text/javascript; charset=utf-8", true;
    "vendor/three/addons/loaders/OBJLoader.js", "text/javascript; charset=utf-8", true;
    "vendor/three/addons/controls/OrbitControls.js", "text/javascript; charset=utf-8", true;
    "vendor/three/addons/utils/BufferGeometryUtils.js", "text/javascript; charset=utf-8", true;
    "vendor/three/addons/utils/SkeletonUtils.js", "text/javascript; charset=utf-8", true;
    "vendor/three/LICENSE", "text/plain; charset=utf-8", false;
    "vendor/uplot/uPlot.iife.min.js", "text/javascript; charset=utf-8", true;
    "vendor/uplot/uPlot.min.css", "text/css; charset=utf-8", true;
    "vendor/uplot/LICENSE", "text/plain; charset=utf-8", false;
}

/// The embedded file `name`, if there is one.
pub fn asset(name: &str) -> Option<&'static Asset> {
    ASSETS.iter().find(|a| a.name == name)
}

/// A JavaScript module of three.js the page imports.
#[derive(Debug, Clone, Copy)]
pub struct Module {
    /// Its name in the page's import map.
    pub key: &'static str,
    /// The embedded asset that holds it.
    pub asset: &'static str,
    /// Its relative imports, each with the import-map name the self-contained report
    /// rewrites it to (a module read from a `data:` URL cannot resolve a relative one).
    pub rewrites: &'static [(&'static str, &'static str)],
}

/// The three.js modules the page imports. The parent steps of the relative imports are
/// spelt with `concat!`, apart from the `/` after them.
pub const MODULES: &[Module] = &[
    Module {
        key: "three",
        asset: "vendor/three/three.module.js",
        rewrites: &[("'./three.core.js'", "'three/core'")],
    },
    Module {
        key: "three/core",
        asset: "vendor/three/three.core.js",
        rewrites: &[],
    },
    Module {
        key: "three/addons/loaders/GLTFLoader.js",
        asset: "vendor/three/addons/loaders/GLTFLoader.js",
        rewrites: &[
            (
                concat!("'..", "/utils/BufferGeometryUtils.js'"),
                "'three/addons/utils/BufferGeometryUtils.js'",
            ),
            (
                concat!("'..", "/utils/SkeletonUtils.js'"),
                "'three/addons/utils/SkeletonUtils.js'",
            ),
        ],
    },
    Module {
        key: "three/addons/loaders/OBJLoader.js",
        asset: "vendor/three/addons/loaders/OBJLoader.js",
        rewrites: &[],
    },
    Module {
        key: "three/addons/controls/OrbitControls.js",
        asset: "vendor/three/addons/controls/OrbitControls.js",
        rewrites: &[],
    },
    Module {
        key: "three/addons/utils/BufferGeometryUtils.js",
        asset: "vendor/three/addons/utils/BufferGeometryUtils.js",
        rewrites: &[],
    },
    Module {
        key: "three/addons/utils/SkeletonUtils.js",
        asset: "vendor/three/addons/utils/SkeletonUtils.js",
        rewrites: &[],
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    const JS: &str = "text/javascript; charset=utf-8";

    #[test]
    fn every_asset_unpacks() {
        for a in ASSETS {
            let bytes = a.unpacked().unwrap();
            assert!(!bytes.is_empty(), "{}", a.name);
            if a.mime == JS {
                std::str::from_utf8(&bytes).unwrap();
            }
        }
    }

    /// A new three.js whose modules import each other differently fails here rather
    /// than in a report that cannot load.
    #[test]
    fn module_rewrites_match_and_leave_no_relative_import() {
        for m in MODULES {
            let mut text = asset(m.asset).unwrap().text().unwrap();
            for (from, to) in m.rewrites {
                assert!(text.contains(from), "{}: {from} not found", m.key);
                text = text.replace(from, to);
            }
            for relative in ["from '.", "import '."] {
                assert!(
                    !text.contains(relative),
                    "{} still imports `{relative}`",
                    m.key
                );
            }
        }
    }
}
