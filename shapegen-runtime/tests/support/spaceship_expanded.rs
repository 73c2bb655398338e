//! The spaceship grammar written out by hand exactly as `generator!` expands it: the
//! contract between the macro and the runtime, and a test grammar for the runtime.
//!
//! The grammar it spells out:
//!
//! ```text
//! generator! {
//!     pub Spaceship {
//!         axiom Start;
//!         node Start {
//!             children { body: Body = 1.0 }
//!             derive(s) { if let Some(body) = body { s.resize(body.size).derive(body); } }
//!         }
//!         node Body {
//!             params { size: Vec3 ~ uniform([0.6; 3], [1.5; 3]) }
//!             children { next: Body = 1.0 / 3.0, wing: Wing = 1.0 / 3.0, top: Top = 1.0 / 3.0 }
//!             derive(s) { ... }
//!         }
//!         node Top { params { size: Vec3 ~ uniform([0.3, 0.1, 0.3], [0.8, 0.2, 0.8]) }
//!                    children { next: TopNext = 1.0 }
//!                    derive(s) { tower_box(s.resize(size), next) } }
//!         node TopNext { params { size: Vec3 ~ uniform([0.6, 0.8, 0.6], [1.1, 1.1, 1.1]) }
//!                        children { next: TopNext = 1.0 } derive(s) { tower_box(s, next) } }
//!         node Wing { params { size: Vec3 ~ uniform([0.3, 0.2, 0.2], [1.2, 0.5, 1.0]),
//!                              shift: f32 ~ uniform(-0.5, 0.5) }
//!                     children { next: WingNext = 1.0 }
//!                     derive(s) { wing_box(s.resize(size), shift, next) } }
//!         node WingNext { params { size: Vec3 ~ uniform([0.6, 0.9, 0.7], [1.2, 1.0, 1.2]),
//!                                  shift: f32 ~ uniform(-0.5, 0.5) }
//!                         children { next: WingNext = 0.9 }
//!                         derive(s) { wing_box(s, shift, next) } }
//!     }
//! }
//! ```
//!
//! Differences from the macro's real output, which a hand-written file cannot reproduce:
//! the runtime is reached through `__rt` instead of `$crate`; the gene variables (`gene`,
//! `shape`, `params`) have mixed-site hygiene there, so user code cannot name them; and
//! the macro writes probabilities as the `f32` literals it evaluated (`0.33333334`).
// The rule bodies keep the braces the macro wraps them in, which the compiler does not
// lint in macro output.
#![allow(dead_code, unused_braces)]

use shapegen_runtime as __rt;

/// Generator `Spaceship`, axiom `Start`, 6 node types. Declared with `generator!`; its
/// derivations run through its `Grammar` implementation.
pub struct Spaceship;

/// Parameters of node `Start` of generator `Spaceship`.
#[repr(C)]
#[derive(
    ::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq,
)]
pub struct Start {}

/// Parameters of node `Body` of generator `Spaceship`.
#[repr(C)]
#[derive(
    ::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq,
)]
pub struct Body {
    /// Parameter `size`.
    pub size: __rt::__private::Vec3,
}

/// Parameters of node `Top` of generator `Spaceship`.
#[repr(C)]
#[derive(
    ::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq,
)]
pub struct Top {
    /// Parameter `size`.
    pub size: __rt::__private::Vec3,
}

/// Parameters of node `TopNext` of generator `Spaceship`.
#[repr(C)]
#[derive(
    ::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq,
)]
pub struct TopNext {
    /// Parameter `size`.
    pub size: __rt::__private::Vec3,
}

/// Parameters of node `Wing` of generator `Spaceship`.
#[repr(C)]
#[derive(
    ::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq,
)]
pub struct Wing {
    /// Parameter `size`.
    pub size: __rt::__private::Vec3,
    /// Parameter `shift`.
    pub shift: ::core::primitive::f32,
}

/// Parameters of node `WingNext` of generator `Spaceship`.
#[repr(C)]
#[derive(
    ::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, ::core::cmp::PartialEq,
)]
pub struct WingNext {
    /// Parameter `size`.
    pub size: __rt::__private::Vec3,
    /// Parameter `shift`.
    pub shift: ::core::primitive::f32,
}

const _: () = {
    use __rt::__private as __p;

    impl __p::NodeParams for Start {
        const KIND: u32 = 0;
        const LINKS: u32 = 1;
        const WORDS: u32 = 0;
        #[inline]
        fn read(_params: &[u32]) -> Self {
            Start {}
        }
        #[inline]
        fn write(&self, _params: &mut [u32]) {}
    }
    impl __p::NodeParams for Body {
        const KIND: u32 = 1;
        const LINKS: u32 = 3;
        const WORDS: u32 = 3;
        #[inline]
        fn read(params: &[u32]) -> Self {
            Self {
                size: __p::read_param(params, 0),
            }
        }
        #[inline]
        fn write(&self, params: &mut [u32]) {
            __p::write_param(params, 0, self.size);
        }
    }
    impl __p::NodeParams for Top {
        const KIND: u32 = 2;
        const LINKS: u32 = 1;
        const WORDS: u32 = 3;
        #[inline]
        fn read(params: &[u32]) -> Self {
            Self {
                size: __p::read_param(params, 0),
            }
        }
        #[inline]
        fn write(&self, params: &mut [u32]) {
            __p::write_param(params, 0, self.size);
        }
    }
    impl __p::NodeParams for TopNext {
        const KIND: u32 = 3;
        const LINKS: u32 = 1;
        const WORDS: u32 = 3;
        #[inline]
        fn read(params: &[u32]) -> Self {
            Self {
                size: __p::read_param(params, 0),
            }
        }
        #[inline]
        fn write(&self, params: &mut [u32]) {
            __p::write_param(params, 0, self.size);
        }
    }
    impl __p::NodeParams for Wing {
        const KIND: u32 = 4;
        const LINKS: u32 = 1;
        const WORDS: u32 = 4;
        #[inline]
        fn read(params: &[u32]) -> Self {
            Self {
                size: __p::read_param(params, 0),
                shift: __p::read_param(params, 3),
            }
        }
        #[inline]
        fn write(&self, params: &mut [u32]) {
            __p::write_param(params, 0, self.size);
            __p::write_param(params, 3, self.shift);
        }
    }
    impl __p::NodeParams for WingNext {
        const KIND: u32 = 5;
        const LINKS: u32 = 1;
        const WORDS: u32 = 4;
        #[inline]
        fn read(params: &[u32]) -> Self {
            Self {
                size: __p::read_param(params, 0),
                shift: __p::read_param(params, 3),
            }
        }
        #[inline]
        fn write(&self, params: &mut [u32]) {
            __p::write_param(params, 0, self.size);
            __p::write_param(params, 3, self.shift);
        }
    }

    const GRAPH: __p::GeneratorGraph = __p::GeneratorGraph {
        name: "Spaceship",
        key: "spaceship",
        axiom: 0,
        meshes: &["cube"],
        nodes: &[
            __p::NodeDesc {
                name: "Start",
                params: &[],
                slots: &[__p::SlotDesc {
                    name: "body",
                    child: 1,
                    probability: 1.0,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 0,
            },
            __p::NodeDesc {
                name: "Body",
                params: &[__p::ParamDesc {
                    name: "size",
                    offset: 0,
                    dist: __p::Distribution::UniformVec3 {
                        lo: [0.6, 0.6, 0.6],
                        hi: [1.5, 1.5, 1.5],
                    },
                }],
                slots: &[
                    __p::SlotDesc {
                        name: "next",
                        child: 1,
                        probability: 1.0 / 3.0,
                        count: 1,
                        first_link: 0,
                    },
                    __p::SlotDesc {
                        name: "wing",
                        child: 4,
                        probability: 1.0 / 3.0,
                        count: 1,
                        first_link: 1,
                    },
                    __p::SlotDesc {
                        name: "top",
                        child: 2,
                        probability: 1.0 / 3.0,
                        count: 1,
                        first_link: 2,
                    },
                ],
                links: 3,
                param_words: 3,
            },
            __p::NodeDesc {
                name: "Top",
                params: &[__p::ParamDesc {
                    name: "size",
                    offset: 0,
                    dist: __p::Distribution::UniformVec3 {
                        lo: [0.3, 0.1, 0.3],
                        hi: [0.8, 0.2, 0.8],
                    },
                }],
                slots: &[__p::SlotDesc {
                    name: "next",
                    child: 3,
                    probability: 1.0,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 3,
            },
            __p::NodeDesc {
                name: "TopNext",
                params: &[__p::ParamDesc {
                    name: "size",
                    offset: 0,
                    dist: __p::Distribution::UniformVec3 {
                        lo: [0.6, 0.8, 0.6],
                        hi: [1.1, 1.1, 1.1],
                    },
                }],
                slots: &[__p::SlotDesc {
                    name: "next",
                    child: 3,
                    probability: 1.0,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 3,
            },
            __p::NodeDesc {
                name: "Wing",
                params: &[
                    __p::ParamDesc {
                        name: "size",
                        offset: 0,
                        dist: __p::Distribution::UniformVec3 {
                            lo: [0.3, 0.2, 0.2],
                            hi: [1.2, 0.5, 1.0],
                        },
                    },
                    __p::ParamDesc {
                        name: "shift",
                        offset: 3,
                        dist: __p::Distribution::Uniform { lo: -0.5, hi: 0.5 },
                    },
                ],
                slots: &[__p::SlotDesc {
                    name: "next",
                    child: 5,
                    probability: 1.0,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 4,
            },
            __p::NodeDesc {
                name: "WingNext",
                params: &[
                    __p::ParamDesc {
                        name: "size",
                        offset: 0,
                        dist: __p::Distribution::UniformVec3 {
                            lo: [0.6, 0.9, 0.7],
                            hi: [1.2, 1.0, 1.2],
                        },
                    },
                    __p::ParamDesc {
                        name: "shift",
                        offset: 3,
                        dist: __p::Distribution::Uniform { lo: -0.5, hi: 0.5 },
                    },
                ],
                slots: &[__p::SlotDesc {
                    name: "next",
                    child: 5,
                    probability: 0.9,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 4,
            },
        ],
    };

    // Each parameter struct holds exactly its gene words (`<=` for nodes with a `bool`,
    // which takes one byte in the struct but a word in the gene), and the graph's offsets
    // agree with the runtime's word sizes.
    const _: () = {
        ::core::assert!(
            ::core::mem::size_of::<Start>() == 0,
            "the parameter struct of node `Start` does not match its gene words"
        );
        ::core::assert!(
            ::core::mem::size_of::<Body>() == 12,
            "the parameter struct of node `Body` does not match its gene words"
        );
        ::core::assert!(
            ::core::mem::size_of::<Top>() == 12,
            "the parameter struct of node `Top` does not match its gene words"
        );
        ::core::assert!(
            ::core::mem::size_of::<TopNext>() == 12,
            "the parameter struct of node `TopNext` does not match its gene words"
        );
        ::core::assert!(
            ::core::mem::size_of::<Wing>() == 16,
            "the parameter struct of node `Wing` does not match its gene words"
        );
        ::core::assert!(
            ::core::mem::size_of::<WingNext>() == 16,
            "the parameter struct of node `WingNext` does not match its gene words"
        );
        ::core::assert!(
            GRAPH.layout_is_consistent(),
            "the generator graph's layout disagrees with the runtime's"
        );
    };

    impl __p::NodeRule<Spaceship> for Start {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, Spaceship>, gene: __p::GeneView<'a>, params: Self) {
            Spaceship::__rule_start(shape, gene, params)
        }
    }

    impl __p::NodeRule<Spaceship> for Body {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, Spaceship>, gene: __p::GeneView<'a>, params: Self) {
            Spaceship::__rule_body(shape, gene, params)
        }
    }

    impl __p::NodeRule<Spaceship> for Top {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, Spaceship>, gene: __p::GeneView<'a>, params: Self) {
            Spaceship::__rule_top(shape, gene, params)
        }
    }

    impl __p::NodeRule<Spaceship> for TopNext {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, Spaceship>, gene: __p::GeneView<'a>, params: Self) {
            Spaceship::__rule_top_next(shape, gene, params)
        }
    }

    impl __p::NodeRule<Spaceship> for Wing {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, Spaceship>, gene: __p::GeneView<'a>, params: Self) {
            Spaceship::__rule_wing(shape, gene, params)
        }
    }

    impl __p::NodeRule<Spaceship> for WingNext {
        #[inline]
        fn derive<'a>(shape: __p::Shape<'a, Spaceship>, gene: __p::GeneView<'a>, params: Self) {
            Spaceship::__rule_wing_next(shape, gene, params)
        }
    }

    impl __p::Grammar for Spaceship {
        const GRAPH: &'static __p::GeneratorGraph = &GRAPH;

        #[inline]
        fn derive_gene<'a>(shape: __p::Shape<'a, Self>, gene: __p::GeneView<'a>) {
            match gene.kind() {
                0 => Self::__rule_start(
                    shape,
                    gene,
                    <Start as __p::NodeParams>::read(
                        gene.params(<Start as __p::NodeParams>::LINKS),
                    ),
                ),
                1 => Self::__rule_body(
                    shape,
                    gene,
                    <Body as __p::NodeParams>::read(gene.params(<Body as __p::NodeParams>::LINKS)),
                ),
                2 => Self::__rule_top(
                    shape,
                    gene,
                    <Top as __p::NodeParams>::read(gene.params(<Top as __p::NodeParams>::LINKS)),
                ),
                3 => Self::__rule_top_next(
                    shape,
                    gene,
                    <TopNext as __p::NodeParams>::read(
                        gene.params(<TopNext as __p::NodeParams>::LINKS),
                    ),
                ),
                4 => Self::__rule_wing(
                    shape,
                    gene,
                    <Wing as __p::NodeParams>::read(gene.params(<Wing as __p::NodeParams>::LINKS)),
                ),
                5 => Self::__rule_wing_next(
                    shape,
                    gene,
                    <WingNext as __p::NodeParams>::read(
                        gene.params(<WingNext as __p::NodeParams>::LINKS),
                    ),
                ),
                _ => {}
            }
        }
    }
};

// The rules live outside `const _` so that nothing declared there (`GRAPH`) can shadow a
// name their bodies use. `s` is the identifier the user chose in `derive(s)`; parameters
// and children are bound under their own names. A node without `derive` gets
// `shape.derive_children(gene, LINKS)`: each present child, in link order, in its scope.
impl Spaceship {
    #[allow(unused_variables)]
    #[inline]
    fn __rule_start<'__a>(
        s: __rt::__private::Shape<'__a, Self>,
        gene: __rt::__private::GeneView<'__a>,
        params: Start,
    ) {
        let body: ::core::option::Option<__rt::__private::Child<'__a, Body>> = gene.child(0);
        {
            if let Some(body) = body {
                s.resize(body.size).derive(body);
            }
        }
    }

    #[allow(unused_variables)]
    #[inline]
    fn __rule_body<'__a>(
        s: __rt::__private::Shape<'__a, Self>,
        gene: __rt::__private::GeneView<'__a>,
        params: Body,
    ) {
        let Body { size } = params;
        let next: ::core::option::Option<__rt::__private::Child<'__a, Body>> = gene.child(0);
        let wing: ::core::option::Option<__rt::__private::Child<'__a, Wing>> = gene.child(1);
        let top: ::core::option::Option<__rt::__private::Child<'__a, Top>> = gene.child(2);
        {
            use glam::vec3;
            let s = s.translate(vec3(0.0, 0.0, s.size().z / 2.0));
            s.emit(__rt::CUBE);
            if let Some(next) = next {
                s.translate(vec3(0.0, 0.0, s.size().z / 2.0))
                    .resize(next.size)
                    .derive(next);
            }
            if let Some(top) = top {
                s.translate(vec3(0.0, s.size().y / 2.0, 0.0)).derive(top);
            }
            if let Some(wing) = wing {
                s.translate(vec3(s.size().x / 2.0, 0.0, 0.0)).derive(wing);
                s.rotate_z(std::f32::consts::PI)
                    .translate(vec3(s.size().x / 2.0, 0.0, 0.0))
                    .derive(wing);
            }
        }
    }

    #[allow(unused_variables)]
    #[inline]
    fn __rule_top<'__a>(
        s: __rt::__private::Shape<'__a, Self>,
        gene: __rt::__private::GeneView<'__a>,
        params: Top,
    ) {
        let Top { size } = params;
        let next: ::core::option::Option<__rt::__private::Child<'__a, TopNext>> = gene.child(0);
        { tower_box(s.resize(size), next) }
    }

    #[allow(unused_variables)]
    #[inline]
    fn __rule_top_next<'__a>(
        s: __rt::__private::Shape<'__a, Self>,
        gene: __rt::__private::GeneView<'__a>,
        params: TopNext,
    ) {
        let TopNext { size } = params;
        let next: ::core::option::Option<__rt::__private::Child<'__a, TopNext>> = gene.child(0);
        { tower_box(s, next) }
    }

    #[allow(unused_variables)]
    #[inline]
    fn __rule_wing<'__a>(
        s: __rt::__private::Shape<'__a, Self>,
        gene: __rt::__private::GeneView<'__a>,
        params: Wing,
    ) {
        let Wing { size, shift } = params;
        let next: ::core::option::Option<__rt::__private::Child<'__a, WingNext>> = gene.child(0);
        { wing_box(s.resize(size), shift, next) }
    }

    #[allow(unused_variables)]
    #[inline]
    fn __rule_wing_next<'__a>(
        s: __rt::__private::Shape<'__a, Self>,
        gene: __rt::__private::GeneView<'__a>,
        params: WingNext,
    ) {
        let WingNext { size, shift } = params;
        let next: ::core::option::Option<__rt::__private::Child<'__a, WingNext>> = gene.child(0);
        { wing_box(s, shift, next) }
    }
}

// The helper functions the grammar's rules call, as `generators::spaceship` defines them.

fn tower_box<'a>(
    s: __rt::__private::Shape<'a, Spaceship>,
    next: Option<__rt::__private::Child<'a, TopNext>>,
) {
    use glam::vec3;
    let s = s.translate(vec3(0.0, s.size().y / 2.0, 0.0));
    s.emit(__rt::CUBE);
    if let Some(next) = next {
        s.translate(vec3(0.0, s.size().y / 2.0, 0.0))
            .resize(next.size)
            .derive(next);
    }
}

fn wing_box<'a>(
    s: __rt::__private::Shape<'a, Spaceship>,
    shift: f32,
    next: Option<__rt::__private::Child<'a, WingNext>>,
) {
    use glam::vec3;
    let s = s.translate(vec3(0.0, 0.0, s.size().z * shift));
    let s = s.translate(vec3(s.size().x / 2.0, 0.0, 0.0));
    s.emit(__rt::CUBE);
    if let Some(next) = next {
        s.translate(vec3(s.size().x / 2.0, 0.0, 0.0))
            .resize(next.size)
            .derive(next);
    }
}
