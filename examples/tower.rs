//! Your own generator with the whole command-line tool: this file is all a crate needs
//! to `sample`, `score`, `target`, `run`, `compare`, `render` and `export` models of its
//! own generator, named in its scenes as `generator = "tower"`.
//!
//! ```sh
//! cargo run --release --example tower -- sample --generator tower -n 8 --out target/tower/samples
//! cargo run --release --example tower -- run examples/tower/tower.toml --cpu --seconds 10 \
//!     --out target/tower/run
//! cargo run --release --example tower -- render examples/tower/tower.toml \
//!     --genomes target/tower/run/best.genome.json --out target/tower/render
//! ```

use shapegen::prelude::*;

generator! {
    /// A tower of stacked storeys, each a little smaller and turned, with balconies.
    pub Tower {
        axiom Base;

        /// The ground storey.
        node Base {
            params { size: Vec3 ~ uniform([2.0, 0.6, 2.0], [4.0, 1.2, 4.0]) }
            children { up: Storey = 0.95 }
            derive(s) {
                let s = s.with_size(size);
                s.translate(vec3(0.0, size.y / 2.0, 0.0)).emit(CUBE);
                if let Some(up) = up {
                    s.translate(vec3(0.0, size.y, 0.0)).derive(up);
                }
            }
        }

        /// One storey above the ground.
        node Storey {
            params {
                /// Size relative to the storey below.
                shrink: Vec3 ~ uniform([0.75, 0.8, 0.75], [1.0, 1.3, 1.0]),
                twist: f32 ~ degrees(-15, 15),
            }
            children { up: Storey = 0.85, balconies: [Balcony; 4] = 0.3 }
            derive(s) {
                let s = s.rotate_y(twist).with_size(s.size() * shrink);
                let h = s.size().y;
                s.translate(vec3(0.0, h / 2.0, 0.0)).emit(CUBE);
                for (side, balcony) in balconies.iter() {
                    let angle = side as f32 * std::f32::consts::FRAC_PI_2;
                    s.translate(vec3(0.0, h / 2.0, 0.0))
                        .rotate_y(angle)
                        .translate(vec3(s.size().x / 2.0, 0.0, 0.0))
                        .derive(balcony);
                }
                if let Some(up) = up {
                    s.translate(vec3(0.0, h, 0.0)).derive(up);
                }
            }
        }

        /// A slab sticking out of a storey's side.
        node Balcony {
            params { depth: f32 ~ uniform(0.2, 0.6) }
            derive(s) {
                s.translate(vec3(depth / 2.0, 0.0, 0.0))
                    .with_size(vec3(depth, 0.15, 1.0))
                    .emit(CUBE);
            }
        }
    }
}

fn main() -> std::process::ExitCode {
    shapegen::cli::Cli::new().generator::<Tower>("tower").run()
}
