//! Expansion: the checked model into Rust items.
//!
//! For `generator! { pub Spaceship { .. } }` the expansion is, in the invocation's scope:
//! - `pub struct Spaceship;`, the grammar;
//! - one `pub const NAME: MeshId` per declared mesh;
//! - one `#[repr(C)]` parameter struct per node, named after it, its fields named after
//!   the parameters;
//! - `impl Spaceship { fn __rule_body(..) .. }`: one rule function per node, where the
//!   user's `derive` body sees the scope under the name it chose, the parameters and the
//!   children under their own names (the parameters are handed to it read). It lives outside the `const _` block below so that
//!   nothing the expansion declares can shadow a name the body uses;
//! - `const _: () = { .. }` holding the `NodeParams` and `NodeRule` impls, the
//!   `GeneratorGraph` constant, compile-time layout asserts and the `Grammar` impl, whose
//!   `derive_gene` matches on the node kind and reads the parameters. A rule function
//!   takes its node's parameters read: `derive_gene` reads them for the root, and a
//!   parent read them with the child (`Child`), so that `s.derive(child)` runs the
//!   child's rule through `NodeRule` without looking its kind up or reading them again.
//!
//! Everything reaches the runtime through the path the runtime's wrapper passed
//! (`$crate::__private`) and the standard library through `::core`, so the expansion does
//! not depend on the user's imports. Identifiers the expansion introduces in the user's
//! rule bodies (the gene) have mixed-site hygiene, so they cannot clash with user names.

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;
use syn::{Attribute, Lifetime};

use crate::check::snake_case;
use crate::layout::{NodeLayout, node_layout};
use crate::model::{AngleUnit, Dist, Generator, Node, Param, ParamType, Rule};

/// What every part of the expansion needs.
pub struct Expander<'a> {
    /// The generator.
    pub g: &'a Generator<'a>,
    /// `$crate::__private`.
    pub p: TokenStream,
}

impl<'a> Expander<'a> {
    /// An expander for `g`, reaching the runtime through `krate`.
    pub fn new(g: &'a Generator<'a>, krate: &TokenStream) -> Self {
        Expander {
            g,
            p: quote!(#krate::__private),
        }
    }

    /// `pub struct Spaceship;`
    pub fn grammar_struct(&self) -> TokenStream {
        let g = self.g;
        let (vis, name) = (g.vis, g.name);
        let axiom = g
            .axiom
            .map(|k| format!(", axiom `{}`", g.nodes[k as usize].name))
            .unwrap_or_default();
        let n = g.nodes.len();
        let doc = format!(
            "Generator `{name}`{axiom}, {n} node type{}. Declared with `generator!`; \
             its derivations run through its `Grammar` implementation.",
            if n == 1 { "" } else { "s" }
        );
        let docs = docs(&doc, g.attrs);
        let attrs = g.attrs;
        quote! {
            #(#attrs)*
            #docs
            #vis struct #name;
        }
    }

    /// One constant per declared mesh.
    pub fn mesh_consts(&self) -> TokenStream {
        let (vis, p, gname) = (self.g.vis, &self.p, self.g.name);
        self.g
            .meshes
            .iter()
            .map(|m| {
                let doc = format!(
                    "Mesh `\"{}\"` of generator `{gname}`: mesh {} of its graph.",
                    m.file, m.id
                );
                let docs = docs(&doc, m.attrs);
                let (attrs, name) = (m.attrs, m.name);
                let id = Literal::u32_unsuffixed(m.id);
                quote! {
                    #(#attrs)*
                    #docs
                    #vis const #name: #p::MeshId = #p::MeshId(#id);
                }
            })
            .collect()
    }

    /// The parameter struct of `node`, with the fields of `params`.
    pub fn param_struct(&self, node: &Node, params: &[&Param]) -> TokenStream {
        let (vis, gname, name) = (self.g.vis, self.g.name, node.name);
        let mut doc = format!("Parameters of node `{name}` of generator `{gname}`.");
        if !node.slots.is_empty() {
            let slots: Vec<String> = node
                .slots
                .iter()
                .map(|s| {
                    let target = match s.array {
                        Some(Some(n)) => format!("[{}; {n}]", s.node),
                        _ => s.node.to_string(),
                    };
                    match s.probability {
                        Some(p) => format!("`{}: {target}` (p = {})", s.name, show_probability(p)),
                        None => format!("`{}: {target}`", s.name),
                    }
                })
                .collect();
            doc += &format!("\n\nChild slots: {}.", slots.join(", "));
        }
        let node_docs = docs(&doc, node.attrs);
        let attrs = node.attrs;
        let fields = params.iter().filter_map(|param| {
            let ty = self.param_type(param.ty?);
            let pname = param.name;
            let doc = match &param.dist {
                Some(d @ Dist::Angle { .. }) => format!(
                    "Parameter `{pname}`, drawn from `{}`; held in radians.",
                    describe(d)
                ),
                Some(d) => format!("Parameter `{pname}`, drawn from `{}`.", describe(d)),
                None => format!("Parameter `{pname}`."),
            };
            let docs = docs(&doc, param.attrs);
            let attrs = param.attrs;
            Some(quote! {
                #(#attrs)*
                #docs
                pub #pname: #ty,
            })
        });
        quote! {
            #(#attrs)*
            #node_docs
            #[repr(C)]
            #[allow(clippy::derive_partial_eq_without_eq)]
            #[derive(
                ::core::clone::Clone,
                ::core::marker::Copy,
                ::core::fmt::Debug,
                ::core::cmp::PartialEq
            )]
            #vis struct #name {
                #(#fields)*
            }
        }
    }

    fn param_type(&self, ty: ParamType) -> TokenStream {
        let p = &self.p;
        match ty {
            ParamType::F32 => quote!(::core::primitive::f32),
            ParamType::Vec2 => quote!(#p::Vec2),
            ParamType::Vec3 => quote!(#p::Vec3),
            ParamType::I32 => quote!(::core::primitive::i32),
            ParamType::U32 => quote!(::core::primitive::u32),
            ParamType::Bool => quote!(::core::primitive::bool),
        }
    }

    /// `impl NodeParams for Node`, reading and writing the fields of `params` (whose
    /// types are known) at consecutive word offsets; `links` is the node's link count.
    pub fn node_params_impl(&self, node: &Node, params: &[&Param], links: u32) -> TokenStream {
        let p = &self.p;
        let name = node.name;
        let words_var = Ident::new("params", Span::mixed_site());
        let typed: Vec<(&Ident, ParamType)> = params
            .iter()
            .filter_map(|param| Some((param.name, param.ty?)))
            .collect();
        let (offsets, words) = crate::layout::param_offsets(typed.iter().map(|&(_, ty)| ty));
        let fields: Vec<&Ident> = typed.iter().map(|&(f, _)| f).collect();
        let offsets: Vec<Literal> = offsets
            .into_iter()
            .map(|o| Literal::usize_unsuffixed(o as usize))
            .collect();
        let (kind, links, words) = (
            Literal::u32_unsuffixed(node.kind),
            Literal::u32_unsuffixed(links),
            Literal::u32_unsuffixed(words),
        );
        let (read, write) = if fields.is_empty() {
            (
                quote! {
                    fn read(_: &[::core::primitive::u32]) -> Self {
                        Self {}
                    }
                },
                quote! {
                    fn write(&self, _: &mut [::core::primitive::u32]) {}
                },
            )
        } else {
            (
                quote! {
                    fn read(#words_var: &[::core::primitive::u32]) -> Self {
                        Self {
                            #(#fields: #p::read_param(#words_var, #offsets),)*
                        }
                    }
                },
                quote! {
                    fn write(&self, #words_var: &mut [::core::primitive::u32]) {
                        #(#p::write_param(#words_var, #offsets, self.#fields);)*
                    }
                },
            )
        };
        quote! {
            impl #p::NodeParams for #name {
                const KIND: ::core::primitive::u32 = #kind;
                const LINKS: ::core::primitive::u32 = #links;
                const WORDS: ::core::primitive::u32 = #words;
                #[inline]
                #read
                #[inline]
                #write
            }
        }
    }

    /// `impl NodeRule` for `node`'s parameters: its rule, run on a child whose
    /// parameters were read when the child was (the slot fixes its node type); with
    /// `has_rule` false (a generator with mistakes, whose rule for the node is not
    /// emitted), a rule that does nothing.
    pub fn node_rule_impl(&self, node: &Node, has_rule: bool) -> TokenStream {
        let (p, grammar, name, f) = (&self.p, self.g.name, node.name, &node.rule_fn);
        let shape = Ident::new("shape", Span::mixed_site());
        let gene = Ident::new("gene", Span::mixed_site());
        let params = Ident::new("params", Span::mixed_site());
        let call = match node.rule {
            _ if !has_rule => quote!(),
            Rule::Default => quote!(#grammar::#f(#shape, #gene)),
            Rule::Body { .. } => quote!(#grammar::#f(#shape, #gene, #params)),
        };
        quote! {
            impl #p::NodeRule<#grammar> for #name {
                #[inline]
                #[allow(unused_variables)]
                fn derive<'a>(#shape: #p::Shape<'a, #grammar>, #gene: #p::GeneView<'a>, #params: Self) {
                    #call
                }
            }
        }
    }

    /// The rule function of `node`.
    pub fn rule_fn(&self, node: &Node, layout: &NodeLayout) -> TokenStream {
        let p = &self.p;
        let f = &node.rule_fn;
        let gene = Ident::new("gene", Span::mixed_site());
        let lt = Lifetime::new("'__a", Span::call_site());
        let links = Literal::u32_unsuffixed(layout.links);
        match &node.rule {
            Rule::Default => {
                let shape = Ident::new("shape", Span::mixed_site());
                let body =
                    (layout.links > 0).then(|| quote!(#shape.derive_children(#gene, #links);));
                quote! {
                    #[allow(unused_variables)]
                    #[inline]
                    fn #f<#lt>(#shape: #p::Shape<#lt, Self>, #gene: #p::GeneView<#lt>) {
                        #body
                    }
                }
            }
            Rule::Body {
                mutability,
                scope,
                body,
            } => {
                let name = node.name;
                let params = Ident::new("params", Span::mixed_site());
                let read = (!node.params.is_empty()).then(|| {
                    let fields = node.params.iter().map(|param| param.name);
                    quote! {
                        let #name { #(#fields),* } = #params;
                    }
                });
                let slots = node.slots.iter().zip(&layout.first_links).map(|(s, &first)| {
                    let (slot, child) = (s.name, s.node);
                    let first = Literal::u32_unsuffixed(first);
                    match s.array {
                        Some(n) => {
                            let n = Literal::usize_unsuffixed(n.unwrap_or(0) as usize);
                            quote! {
                                let #slot: #p::Slots<#lt, #child, #n> = #p::Slots::new(#gene, #first);
                            }
                        }
                        None => quote! {
                            let #slot: ::core::option::Option<#p::Child<#lt, #child>> =
                                #gene.child(#first);
                        },
                    }
                });
                // A one-expression body `derive(s) { rule(s) }` is still the user's block.
                quote! {
                    #[allow(unused_variables, unused_braces)]
                    #[inline]
                    fn #f<#lt>(
                        #mutability #scope: #p::Shape<#lt, Self>,
                        #gene: #p::GeneView<#lt>,
                        #params: #name,
                    ) {
                        #read
                        #(#slots)*
                        #body
                    }
                }
            }
        }
    }

    /// `impl Grammar`: `GRAPH` and the `match` over node kinds.
    fn grammar_impl(&self, graph: TokenStream, arms: TokenStream) -> TokenStream {
        let (p, name) = (&self.p, self.g.name);
        let shape = Ident::new("shape", Span::mixed_site());
        let gene = Ident::new("gene", Span::mixed_site());
        quote! {
            impl #p::Grammar for #name {
                const GRAPH: &'static #p::GeneratorGraph = #graph;
                #[inline]
                fn derive_gene<'a>(#shape: #p::Shape<'a, Self>, #gene: #p::GeneView<'a>) {
                    #arms
                }
            }
        }
    }

    /// The `Grammar` impl of a generator whose checks failed: an empty graph and no
    /// rules, enough for the rest of the user's crate to type-check.
    pub fn stub_grammar_impl(&self) -> TokenStream {
        let p = &self.p;
        let name = plain(self.g.name);
        let key = snake_case(&name);
        let graph = quote! {
            &#p::GeneratorGraph {
                name: #name,
                key: #key,
                axiom: 0,
                nodes: &[],
                meshes: &["cube"],
            }
        };
        self.grammar_impl(graph, quote!())
    }

    /// The whole expansion of a generator that passed every check; `None` if some part is
    /// unknown after all (which the checks rule out).
    pub fn expand(&self) -> Option<TokenStream> {
        let g = self.g;
        let p = &self.p;
        let name = g.name;
        let layouts: Vec<NodeLayout> = g.nodes.iter().map(node_layout).collect::<Option<_>>()?;
        let axiom = Literal::u32_unsuffixed(g.axiom?);

        let grammar_struct = self.grammar_struct();
        let mesh_consts = self.mesh_consts();
        let mut structs = TokenStream::new();
        let mut impls = TokenStream::new();
        let mut rules = TokenStream::new();
        let mut descs = Vec::new();
        let mut asserts = TokenStream::new();
        let mut arms = TokenStream::new();
        for (node, layout) in g.nodes.iter().zip(&layouts) {
            let params: Vec<&Param> = node.params.iter().collect();
            structs.extend(self.param_struct(node, &params));
            impls.extend(self.node_params_impl(node, &params, layout.links));
            rules.extend(self.rule_fn(node, layout));
            descs.push(self.node_desc(node, layout)?);

            asserts.extend(size_assert(node, layout));
            arms.extend(dispatch_arm(p, node, layout));
            impls.extend(self.node_rule_impl(node, true));
        }
        let gene = Ident::new("gene", Span::mixed_site());
        let arms = quote! {
            match #gene.kind() {
                #arms
                _ => {}
            }
        };
        let graph_name = plain(name);
        let graph_key = snake_case(&graph_name);
        let meshes =
            std::iter::once("cube".to_owned()).chain(g.meshes.iter().map(|m| m.file.clone()));
        let grammar_impl = self.grammar_impl(quote!(&GRAPH), arms);
        Some(quote! {
            #grammar_struct
            #mesh_consts
            #structs

            impl #name {
                #rules
            }

            const _: () = {
                #impls

                // Bounds written as `PI / 2.0` become the literal `1.5707964`.
                #[allow(clippy::approx_constant)]
                const GRAPH: #p::GeneratorGraph = #p::GeneratorGraph {
                    name: #graph_name,
                    key: #graph_key,
                    axiom: #axiom,
                    meshes: &[#(#meshes),*],
                    nodes: &[#(#descs),*],
                };

                // Each parameter struct holds exactly its gene words, and the graph's
                // offsets agree with the runtime's word sizes.
                const _: () = {
                    #asserts
                    ::core::assert!(
                        GRAPH.layout_is_consistent(),
                        "the generator graph's layout disagrees with the runtime's"
                    );
                };

                #grammar_impl
            };
        })
    }

    /// The `NodeDesc` of `node`.
    fn node_desc(&self, node: &Node, layout: &NodeLayout) -> Option<TokenStream> {
        let p = &self.p;
        let name = plain(node.name);
        let params = node
            .params
            .iter()
            .zip(&layout.offsets)
            .map(|(param, &offset)| {
                let pname = plain(param.name);
                let offset = Literal::u32_unsuffixed(offset);
                let dist = self.dist(param.dist.as_ref()?);
                Some(quote!(#p::ParamDesc { name: #pname, offset: #offset, dist: #dist }))
            })
            .collect::<Option<Vec<_>>>()?;
        let slots = node
            .slots
            .iter()
            .zip(&layout.first_links)
            .map(|(s, &first)| {
                let sname = plain(s.name);
                let child = Literal::u32_unsuffixed(s.child?);
                let probability = f32_lit(s.probability?);
                let count = Literal::u32_unsuffixed(s.count()?);
                let first = Literal::u32_unsuffixed(first);
                Some(quote! {
                    #p::SlotDesc {
                        name: #sname,
                        child: #child,
                        probability: #probability,
                        count: #count,
                        first_link: #first,
                    }
                })
            })
            .collect::<Option<Vec<_>>>()?;
        let links = Literal::u32_unsuffixed(layout.links);
        let words = Literal::u32_unsuffixed(layout.words);
        Some(quote! {
            #p::NodeDesc {
                name: #name,
                params: &[#(#params),*],
                slots: &[#(#slots),*],
                links: #links,
                param_words: #words,
            }
        })
    }

    /// A `Distribution` value.
    fn dist(&self, d: &Dist) -> TokenStream {
        let p = &self.p;
        let arr = |v: &[f32]| {
            let v = v.iter().map(|&x| f32_lit(x));
            quote!([#(#v),*])
        };
        match d {
            Dist::Uniform { lo, hi } => {
                let (lo, hi) = (f32_lit(*lo), f32_lit(*hi));
                quote!(#p::Distribution::Uniform { lo: #lo, hi: #hi })
            }
            Dist::Angle { lo, hi, unit, .. } => {
                let (lo, hi) = (f32_lit(*lo), f32_lit(*hi));
                let unit = match unit {
                    AngleUnit::Degrees => quote!(#p::AngleUnit::Degrees),
                    AngleUnit::Radians => quote!(#p::AngleUnit::Radians),
                };
                quote!(#p::Distribution::Angle { lo: #lo, hi: #hi, unit: #unit })
            }
            Dist::UniformVec2 { lo, hi } => {
                let (lo, hi) = (arr(lo), arr(hi));
                quote!(#p::Distribution::UniformVec2 { lo: #lo, hi: #hi })
            }
            Dist::UniformVec3 { lo, hi } => {
                let (lo, hi) = (arr(lo), arr(hi));
                quote!(#p::Distribution::UniformVec3 { lo: #lo, hi: #hi })
            }
            Dist::Int { lo, hi } => {
                let (lo, hi) = (i32_lit(*lo), i32_lit(*hi));
                quote!(#p::Distribution::Int { lo: #lo, hi: #hi })
            }
            Dist::Index { lo, hi } => {
                let (lo, hi) = (Literal::u32_unsuffixed(*lo), Literal::u32_unsuffixed(*hi));
                quote!(#p::Distribution::Index { lo: #lo, hi: #hi })
            }
            Dist::Weighted { weights } => {
                let w = arr(weights);
                quote!(#p::Distribution::Weighted { weights: &#w })
            }
            Dist::Bernoulli { p: prob } => {
                let prob = f32_lit(*prob);
                quote!(#p::Distribution::Bernoulli { p: #prob })
            }
        }
    }
}

/// A name as the generator graph stores it: without `r#`.
fn plain(ident: &Ident) -> String {
    ident.unraw().to_string()
}

/// `default` as a doc attribute, after a paragraph break if `attrs` hold docs of their
/// own: the expansion puts it after the user's attributes, so the user's first line is
/// the item's summary.
fn docs(default: &str, attrs: &[Attribute]) -> TokenStream {
    let user_docs = attrs.iter().any(|a| a.path().is_ident("doc"));
    let sep = user_docs.then(|| quote!(#[doc = ""]));
    quote! {
        #sep
        #[doc = #default]
    }
}

/// A probability as people write it: at most four decimals, `0.3333` for `1.0 / 3.0`.
fn show_probability(p: f32) -> String {
    let s = format!("{p:.4}");
    let s = s.trim_end_matches('0');
    s.strip_suffix('.')
        .map_or_else(|| s.to_owned(), |s| format!("{s}.0"))
}

/// How a distribution reads in documentation.
pub fn describe(d: &Dist) -> String {
    match d {
        Dist::Uniform { lo, hi } => format!("uniform({lo:?}, {hi:?})"),
        Dist::Angle {
            unit: AngleUnit::Degrees,
            written: (lo, hi),
            ..
        } => format!("degrees({lo:?}, {hi:?})"),
        Dist::Angle { lo, hi, .. } => format!("radians({lo:?}, {hi:?})"),
        Dist::UniformVec2 { lo, hi } => format!("uniform({lo:?}, {hi:?})"),
        Dist::UniformVec3 { lo, hi } => format!("uniform({lo:?}, {hi:?})"),
        Dist::Int { lo, hi } => format!("uniform({lo}..={hi})"),
        Dist::Index { lo, hi } => format!("uniform({lo}..={hi})"),
        Dist::Weighted { weights } => format!("weighted({weights:?})"),
        Dist::Bernoulli { p } => format!("bernoulli({p:?})"),
    }
}

/// An `f32` literal, negative values as a negation (a literal token has no sign).
pub fn f32_lit(v: f32) -> TokenStream {
    let v = if v.is_finite() { v } else { 0.0 };
    let lit = Literal::f32_unsuffixed(v.abs());
    if v.is_sign_negative() {
        quote!(-#lit)
    } else {
        quote!(#lit)
    }
}

/// An `i32` literal, negative values as a negation.
fn i32_lit(v: i32) -> TokenStream {
    let lit = Literal::u32_unsuffixed(v.unsigned_abs());
    if v < 0 { quote!(-#lit) } else { quote!(#lit) }
}

/// The assertion that `node`'s parameter struct holds exactly its gene words (`bool`
/// takes one byte in the struct but a whole word in the gene, so there at most).
fn size_assert(node: &Node, layout: &NodeLayout) -> TokenStream {
    let ty = node.name;
    let bytes = Literal::usize_unsuffixed(4 * layout.words as usize);
    let msg = format!("the parameter struct of node `{ty}` does not match its gene words");
    if node.params.iter().any(|q| q.ty == Some(ParamType::Bool)) {
        quote!(::core::assert!(::core::mem::size_of::<#ty>() <= #bytes, #msg);)
    } else {
        quote!(::core::assert!(::core::mem::size_of::<#ty>() == #bytes, #msg);)
    }
}

/// The arm of the rule dispatch that runs `node`'s rule on a gene of its kind.
fn dispatch_arm(p: &TokenStream, node: &Node, layout: &NodeLayout) -> TokenStream {
    let (kind, f, name) = (Literal::u32_unsuffixed(node.kind), &node.rule_fn, node.name);
    let shape = Ident::new("shape", Span::mixed_site());
    let gene = Ident::new("gene", Span::mixed_site());
    match node.rule {
        Rule::Default => quote!(#kind => Self::#f(#shape, #gene),),
        Rule::Body { .. } => {
            let links = Literal::u32_unsuffixed(layout.links);
            quote! {
                #kind => Self::#f(#shape, #gene, <#name as #p::NodeParams>::read(#gene.params(#links))),
            }
        }
    }
}
