//! A city grammar written out by hand as `generator!` expands it: an array slot and every
//! parameter type, for the runtime's tests.
//!
//! The grammar it spells out:
//!
//! ```text
//! generator! {
//!     pub City {
//!         axiom Start;
//!         node Start {
//!             children { lots: [Lot; 100] = 0.33 }
//!             derive(s) { for (i, lot) in lots.iter() { s.translate(grid(i)).derive(lot); } }
//!         }
//!         node Lot {
//!             children { building: Building = 1.0 }
//!             derive(s) { if let Some(b) = building { s.derive(b); } }
//!         }
//!         node Building {
//!             params {
//!                 footprint: Vec2 ~ uniform([0.44, 0.44], [1.98, 1.98]),
//!                 height: f32 ~ uniform(0.36, 10.0),
//!                 rotation: f32 ~ angle(0.0, 180.0) degrees,
//!                 style: u32 ~ weighted([0.5, 0.0, 0.3, 0.2]),
//!                 floors: i32 ~ int(-2, 5),
//!                 lit: bool ~ bernoulli(0.3),
//!                 block: u32 ~ index(1, 4),
//!             }
//!             children { roof: Roof = 0.5 }
//!             derive(s) { ... }
//!         }
//!         node Roof {
//!             params { pitch: f32 ~ angle(0.1, 1.2) radians }
//!             children { spire: Roof = 0.4 }
//!             derive(s) { ... }
//!         }
//!     }
//! }
//! ```
#![allow(dead_code, clippy::erasing_op, clippy::identity_op)]

use shapegen_runtime as __rt;

/// Generator `City`.
pub struct City;

/// Parameters of node `Start` of generator `City`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Start {}

/// Parameters of node `Lot` of generator `City`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lot {}

/// Parameters of node `Building` of generator `City`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Building {
    /// Parameter `footprint`.
    pub footprint: __rt::__private::Vec2,
    /// Parameter `height`.
    pub height: f32,
    /// Parameter `rotation`.
    pub rotation: f32,
    /// Parameter `style`.
    pub style: u32,
    /// Parameter `floors`.
    pub floors: i32,
    /// Parameter `lit`.
    pub lit: bool,
    /// Parameter `block`.
    pub block: u32,
}

/// Parameters of node `Roof` of generator `City`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Roof {
    /// Parameter `pitch`.
    pub pitch: f32,
}

const _: () = {
    use __rt::__private as __p;

    // Gene sizes: 2 header words + links + parameter words.
    const _: () = assert!(GRAPH.nodes[0].gene_words() == 2 + 100 + 0);
    const _: () = assert!(GRAPH.nodes[1].gene_words() == 2 + 1 + 0);
    const _: () = assert!(GRAPH.nodes[2].gene_words() == 2 + 1 + 8);
    const _: () = assert!(GRAPH.nodes[3].gene_words() == 2 + 1 + 1);

    impl __p::NodeParams for Start {
        const KIND: u32 = 0;
        const LINKS: u32 = 100;
        const WORDS: u32 = 0;
        #[inline]
        fn read(_params: &[u32]) -> Self {
            Start {}
        }
        #[inline]
        fn write(&self, _params: &mut [u32]) {}
    }
    impl __p::NodeParams for Lot {
        const KIND: u32 = 1;
        const LINKS: u32 = 1;
        const WORDS: u32 = 0;
        #[inline]
        fn read(_params: &[u32]) -> Self {
            Lot {}
        }
        #[inline]
        fn write(&self, _params: &mut [u32]) {}
    }
    impl __p::NodeParams for Building {
        const KIND: u32 = 2;
        const LINKS: u32 = 1;
        const WORDS: u32 = 8;
        #[inline]
        fn read(params: &[u32]) -> Self {
            Building {
                footprint: __p::read_param(params, 0),
                height: __p::read_param(params, 2),
                rotation: __p::read_param(params, 3),
                style: __p::read_param(params, 4),
                floors: __p::read_param(params, 5),
                lit: __p::read_param(params, 6),
                block: __p::read_param(params, 7),
            }
        }
        #[inline]
        fn write(&self, params: &mut [u32]) {
            __p::write_param(params, 0, self.footprint);
            __p::write_param(params, 2, self.height);
            __p::write_param(params, 3, self.rotation);
            __p::write_param(params, 4, self.style);
            __p::write_param(params, 5, self.floors);
            __p::write_param(params, 6, self.lit);
            __p::write_param(params, 7, self.block);
        }
    }
    impl __p::NodeParams for Roof {
        const KIND: u32 = 3;
        const LINKS: u32 = 1;
        const WORDS: u32 = 1;
        #[inline]
        fn read(params: &[u32]) -> Self {
            Roof {
                pitch: __p::read_param(params, 0),
            }
        }
        #[inline]
        fn write(&self, params: &mut [u32]) {
            __p::write_param(params, 0, self.pitch);
        }
    }

    const GRAPH: __p::GeneratorGraph = __p::GeneratorGraph {
        name: "City",
        key: "city",
        axiom: 0,
        meshes: &["cube"],
        nodes: &[
            __p::NodeDesc {
                name: "Start",
                params: &[],
                slots: &[__p::SlotDesc {
                    name: "lots",
                    child: 1,
                    probability: 0.33,
                    count: 100,
                    first_link: 0,
                }],
                links: 100,
                param_words: 0,
            },
            __p::NodeDesc {
                name: "Lot",
                params: &[],
                slots: &[__p::SlotDesc {
                    name: "building",
                    child: 2,
                    probability: 1.0,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 0,
            },
            __p::NodeDesc {
                name: "Building",
                params: &[
                    __p::ParamDesc {
                        name: "footprint",
                        offset: 0,
                        dist: __p::Distribution::UniformVec2 {
                            lo: [0.44, 0.44],
                            hi: [1.98, 1.98],
                        },
                    },
                    __p::ParamDesc {
                        name: "height",
                        offset: 2,
                        dist: __p::Distribution::Uniform { lo: 0.36, hi: 10.0 },
                    },
                    __p::ParamDesc {
                        name: "rotation",
                        offset: 3,
                        dist: __p::Distribution::Angle {
                            lo: 0.0,
                            hi: ::core::f32::consts::PI,
                            unit: __p::AngleUnit::Degrees,
                        },
                    },
                    __p::ParamDesc {
                        name: "style",
                        offset: 4,
                        dist: __p::Distribution::Weighted {
                            weights: &[0.5, 0.0, 0.3, 0.2],
                        },
                    },
                    __p::ParamDesc {
                        name: "floors",
                        offset: 5,
                        dist: __p::Distribution::Int { lo: -2, hi: 5 },
                    },
                    __p::ParamDesc {
                        name: "lit",
                        offset: 6,
                        dist: __p::Distribution::Bernoulli { p: 0.3 },
                    },
                    __p::ParamDesc {
                        name: "block",
                        offset: 7,
                        dist: __p::Distribution::Index { lo: 1, hi: 4 },
                    },
                ],
                slots: &[__p::SlotDesc {
                    name: "roof",
                    child: 3,
                    probability: 0.5,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 8,
            },
            __p::NodeDesc {
                name: "Roof",
                params: &[__p::ParamDesc {
                    name: "pitch",
                    offset: 0,
                    dist: __p::Distribution::Angle {
                        lo: 0.1,
                        hi: 1.2,
                        unit: __p::AngleUnit::Radians,
                    },
                }],
                slots: &[__p::SlotDesc {
                    name: "spire",
                    child: 3,
                    probability: 0.4,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 1,
            },
        ],
    };

    impl __p::NodeRule<City> for Start {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, City>, gene: __p::GeneView<'a>, params: Self) {
            City::__rule_start(shape, gene, params)
        }
    }

    impl __p::NodeRule<City> for Lot {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, City>, gene: __p::GeneView<'a>, params: Self) {
            City::__rule_lot(shape, gene, params)
        }
    }

    impl __p::NodeRule<City> for Building {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, City>, gene: __p::GeneView<'a>, params: Self) {
            City::__rule_building(shape, gene, params)
        }
    }

    impl __p::NodeRule<City> for Roof {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, City>, gene: __p::GeneView<'a>, params: Self) {
            City::__rule_roof(shape, gene, params)
        }
    }

    impl __p::Grammar for City {
        const GRAPH: &'static __p::GeneratorGraph = &GRAPH;

        #[inline]
        fn derive_gene<'a>(shape: __p::Shape<'a, Self>, gene: __p::GeneView<'a>) {
            match gene.kind() {
                0 => City::__rule_start(
                    shape,
                    gene,
                    <Start as __p::NodeParams>::read(
                        gene.params(<Start as __p::NodeParams>::LINKS),
                    ),
                ),
                1 => City::__rule_lot(
                    shape,
                    gene,
                    <Lot as __p::NodeParams>::read(gene.params(<Lot as __p::NodeParams>::LINKS)),
                ),
                2 => City::__rule_building(
                    shape,
                    gene,
                    <Building as __p::NodeParams>::read(
                        gene.params(<Building as __p::NodeParams>::LINKS),
                    ),
                ),
                3 => City::__rule_roof(
                    shape,
                    gene,
                    <Roof as __p::NodeParams>::read(gene.params(<Roof as __p::NodeParams>::LINKS)),
                ),
                _ => {}
            }
        }
    }
};

impl City {
    #[allow(unused_variables)]
    #[inline]
    fn __rule_start<'a>(
        s: __rt::__private::Shape<'a, Self>,
        gene: __rt::__private::GeneView<'a>,
        params: Start,
    ) {
        let lots: __rt::__private::Slots<'a, Lot, 100> = __rt::__private::Slots::new(gene, 0);
        {
            use glam::vec3;
            for (i, lot) in lots.iter() {
                let (x, z) = ((i % 10) as f32, (i / 10) as f32);
                s.translate(vec3(-9.9 + 2.2 * x, 0.0, -9.9 + 2.2 * z))
                    .derive(lot);
            }
        }
    }

    #[allow(unused_variables)]
    #[inline]
    fn __rule_lot<'a>(
        s: __rt::__private::Shape<'a, Self>,
        gene: __rt::__private::GeneView<'a>,
        params: Lot,
    ) {
        let building: Option<__rt::__private::Child<'a, Building>> = gene.child(0);
        {
            if let Some(building) = building {
                s.derive(building);
            }
        }
    }

    #[allow(unused_variables)]
    #[inline]
    fn __rule_building<'a>(
        s: __rt::__private::Shape<'a, Self>,
        gene: __rt::__private::GeneView<'a>,
        params: Building,
    ) {
        let Building {
            footprint,
            height,
            rotation,
            style,
            floors,
            lit,
            block,
        } = params;
        let roof: Option<__rt::__private::Child<'a, Roof>> = gene.child(0);
        {
            use glam::vec3;
            let s = s
                .rotate_y(rotation)
                .with_size(vec3(footprint.x, height, footprint.y))
                .translate(vec3(0.0, height / 2.0, 0.0));
            if lit || style != 1 || floors >= -2 || block > 0 {
                s.emit(__rt::CUBE);
            }
            if let Some(roof) = roof {
                s.translate(vec3(0.0, height / 2.0, 0.0)).derive(roof);
            }
        }
    }

    #[allow(unused_variables)]
    #[inline]
    fn __rule_roof<'a>(
        s: __rt::__private::Shape<'a, Self>,
        gene: __rt::__private::GeneView<'a>,
        params: Roof,
    ) {
        let Roof { pitch } = params;
        let spire: Option<__rt::__private::Child<'a, Roof>> = gene.child(0);
        {
            use glam::vec3;
            let s = s.rotate_x(pitch).resize(vec3(0.8, 0.5, 0.8));
            s.emit(__rt::CUBE);
            if let Some(spire) = spire {
                s.translate(vec3(0.0, s.size().y, 0.0)).derive(spire);
            }
        }
    }
}
