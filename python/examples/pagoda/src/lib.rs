//! A generator of one's own, as a Python package: `pip install .` here builds the
//! `pagoda` module, which offers everything the `shapegen` module does (scenes,
//! searches, models as numpy arrays) for the Pagoda generator and the published ones.
//!
//! ```python
//! import pagoda
//! pagoda.generators()[0]          # "pagoda"
//! g = pagoda.generator("pagoda")
//! model = g.model(g.sample(1, seed=1)[0])
//! ```

use shapegen::prelude::*;

generator! {
    /// A pagoda: a podium, then storeys, each under its own wide eaves, narrowing as they
    /// rise, and a spire on the last.
    pub Pagoda {
        axiom Podium;

        /// The stone base.
        node Podium {
            params { size: Vec3 ~ uniform([4.0, 0.4, 4.0], [7.0, 1.0, 7.0]) }
            children { up: Storey = 1.0 }
            derive(s) {
                let s = s.with_size(size);
                s.translate(vec3(0.0, size.y / 2.0, 0.0)).emit(CUBE);
                if let Some(up) = up {
                    let width = size.x.min(size.z) * 0.7;
                    s.translate(vec3(0.0, size.y, 0.0))
                        .with_size(vec3(width, 1.0, width))
                        .derive(up);
                }
            }
        }

        /// A storey: walls, then eaves a little wider than the walls.
        node Storey {
            params {
                height: f32 ~ uniform(0.8, 1.6),
                eaves: f32 ~ uniform(1.1, 1.5),
                narrowing: f32 ~ uniform(0.7, 0.95),
            }
            children { up: Storey = 0.75, spire: Spire = 0.5 }
            derive(s) {
                let width = s.size().x;
                s.with_size(vec3(width, height, width))
                    .translate(vec3(0.0, height / 2.0, 0.0))
                    .emit(CUBE);
                let roof = s.translate(vec3(0.0, height, 0.0));
                roof.with_size(vec3(width * eaves, 0.15, width * eaves)).emit(CUBE);
                let top = roof.translate(vec3(0.0, 0.075, 0.0));
                if let Some(up) = up {
                    let w = width * narrowing;
                    top.with_size(vec3(w, 1.0, w)).derive(up);
                }
                if let Some(spire) = spire {
                    top.derive(spire);
                }
            }
        }

        /// The finial on the top roof.
        node Spire {
            params { height: f32 ~ uniform(0.5, 2.5) }
            derive(s) {
                s.with_size(vec3(0.15, height, 0.15))
                    .translate(vec3(0.0, height / 2.0, 0.0))
                    .emit(CUBE);
            }
        }
    }
}

shapegen_python::module!(pagoda, published, [Pagoda]);
