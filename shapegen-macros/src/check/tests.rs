//! Each check fires on its mistake, and only there.

use proc_macro2::TokenStream;
use quote::quote;

use super::*;
use crate::parse::parse_input;

/// The messages of every error the parser and the checks report for `body`, the inside
/// of a generator named `G`.
fn errors(body: TokenStream) -> Vec<String> {
    let cx = Ctxt::default();
    match parse_input(quote!(krate; G { #body }), &cx) {
        Ok(input) => {
            let _ = check(&input.generator, &cx);
        }
        Err(e) => cx.push(e),
    }
    cx.finish().iter().map(ToString::to_string).collect()
}

/// Asserts that `body` gives exactly one error, containing `needle`.
#[track_caller]
fn one_error(body: TokenStream, needle: &str) {
    let errs = errors(body);
    assert_eq!(
        errs.len(),
        1,
        "expected one error with {needle:?}, got {errs:#?}"
    );
    assert!(
        errs[0].contains(needle),
        "expected {needle:?} in {:?}",
        errs[0]
    );
}

/// A grammar with one node `Start` holding `params`.
fn with_params(params: TokenStream) -> TokenStream {
    quote! { axiom Start; node Start { params { #params } } }
}

#[test]
fn a_sound_grammar_has_no_errors() {
    let errs = errors(quote! {
        axiom Start;
        meshes { TRUNK = "trunk", LEAF = "leaf" }
        /// Docs.
        node Start {
            params {
                a: f32 ~ uniform(0.0, 1.0),
                b: f32 ~ degrees(0, 120),
                c: f32 ~ radians(-PI, PI),
                d: Vec2 ~ uniform([0.0; 2], [1.0, 2.0]),
                e: Vec3 ~ uniform([0.5; 3], [0.5; 3]),
                f: i32 ~ uniform(-3..=3),
                g: u32 ~ uniform(0..4),
                h: u32 ~ weighted([0.0, 2.0, 1.0]),
                i: bool ~ bernoulli(0.5),
            }
            children { lots: [Lot; 10 * 10] = 0.33, next: Start = 0 }
            derive(mut s) { s = s.translate(Vec3::X); }
        }
        node Lot {}
    });
    assert!(errs.is_empty(), "{errs:#?}");
}

#[test]
fn unknown_child_lists_the_nodes_and_suggests() {
    one_error(
        quote! { axiom Start; node Start { children { b: Bdy = 1.0 } } node Body {} },
        "unknown node `Bdy`; did you mean `Body`? The declared nodes are `Start`, `Body`",
    );
}

#[test]
fn probabilities() {
    let g = |p: TokenStream| quote! { axiom Start; node Start { children { s: Start = #p } } };
    one_error(g(quote!(1.5)), "probability 1.5 is outside [0, 1]");
    one_error(g(quote!(-0.1)), "outside [0, 1]");
    one_error(g(quote!(0.0 / 0.0)), "not a finite number");
    one_error(g(quote!(p)), "the macro cannot evaluate `p`");
}

#[test]
fn float_ranges() {
    one_error(
        with_params(quote!(a: f32 ~ uniform(1.0, 0.0))),
        "empty range",
    );
    one_error(with_params(quote!(a: f32 ~ degrees(90, 0))), "empty range");
    one_error(
        with_params(quote!(a: Vec3 ~ uniform([0.0, 1.0, 0.0], [1.0, 0.5, 1.0]))),
        "empty range in component y",
    );
    one_error(
        with_params(quote!(a: Vec3 ~ uniform([1.5; 3], [0.6; 3]))),
        "empty range in components x, y, z: the upper bound 0.6 is below the lower bound 1.5",
    );
    one_error(
        with_params(quote!(a: Vec2 ~ uniform([0.0; 2], [1.0; 3]))),
        "a Vec2 bound has 2 components, found 3",
    );
    one_error(
        with_params(quote!(a: Vec3 ~ uniform([0.0, 1.0], [1.0; 3]))),
        "a Vec3 bound has 3 components, found 2",
    );
    one_error(
        with_params(quote!(a: Vec3 ~ uniform(0.0, 1.0))),
        "the bounds of a `Vec3` parameter are arrays",
    );
    one_error(
        with_params(quote!(a: f32 ~ uniform(0.0))),
        "takes 2 arguments",
    );
}

#[test]
fn integer_ranges() {
    one_error(with_params(quote!(a: i32 ~ uniform(3..3))), "write `3..=3`");
    one_error(
        with_params(quote!(a: i32 ~ uniform(3..=2))),
        "is empty: 2 is below 3",
    );
    one_error(
        with_params(quote!(a: u32 ~ uniform(-1..=2))),
        "does not fit a `u32`",
    );
    one_error(with_params(quote!(a: i32 ~ uniform(0, 5))), "takes a range");
    one_error(
        with_params(quote!(a: i32 ~ uniform(0..))),
        "needs both ends",
    );
    one_error(
        with_params(quote!(a: i32 ~ uniform(0..=1.5))),
        "found a float",
    );
}

#[test]
fn weights_and_bernoulli() {
    one_error(
        with_params(quote!(a: u32 ~ weighted([]))),
        "at least one weight",
    );
    one_error(
        with_params(quote!(a: u32 ~ weighted([1.0, -1.0]))),
        "weight -1.0 is negative",
    );
    one_error(
        with_params(quote!(a: u32 ~ weighted([0.0; 3]))),
        "every weight is zero",
    );
    one_error(
        with_params(quote!(a: u32 ~ weighted(1.0))),
        "takes an array of weights",
    );
    one_error(
        with_params(quote!(a: bool ~ bernoulli(2.0))),
        "probability 2.0 is outside",
    );
}

#[test]
fn types_and_distributions() {
    one_error(
        with_params(quote!(a: f64 ~ uniform(0.0, 1.0))),
        "unsupported parameter type `f64`; the supported types are `f32`, `Vec2`",
    );
    one_error(
        with_params(quote!(a: f32 ~ weighted([1.0]))),
        "`weighted` does not apply to an `f32` parameter",
    );
    one_error(
        with_params(quote!(a: f32 ~ normal(0.0, 1.0))),
        "unknown distribution `normal`",
    );
    one_error(
        with_params(quote!(a: bool ~ uniform(0, 1))),
        "takes `bernoulli(p)`",
    );
}

#[test]
fn duplicates() {
    one_error(
        quote! { axiom Start; node Start {} node Start {} },
        "node `Start` is declared twice",
    );
    one_error(
        with_params(quote!(a: f32 ~ uniform(0.0, 1.0), a: f32 ~ uniform(0.0, 1.0))),
        "parameter `a` is declared twice",
    );
    one_error(
        quote! { axiom Start; node Start { children { a: Start = 0.5, a: Start = 0.5 } } },
        "child slot `a` is declared twice",
    );
    one_error(
        quote! {
            axiom Start;
            node Start { params { a: f32 ~ uniform(0.0, 1.0) } children { a: Other = 0.5 } }
            node Other {}
        },
        "a parameter and a child slot both named `a`",
    );
    one_error(
        quote! { axiom Start; node Start { params { s: f32 ~ uniform(0.0, 1.0) } derive(s) {} } },
        "the rule's scope is named `s`",
    );
    one_error(
        quote! { axiom Start; node Start { params {} params {} } },
        "has a second `params` section",
    );
    one_error(
        quote! { axiom Start; node Start { derive(s) {} derive(s) {} } },
        "has a second `derive` section",
    );
    one_error(
        quote! { axiom Start; meshes { A = "a", B = "a" } node Start {} },
        "mesh \"a\" is declared twice",
    );
    one_error(
        quote! { axiom Start; meshes { A = "a", A = "b" } node Start {} },
        "mesh constant `A` is declared twice",
    );
    one_error(
        quote! { axiom Start; meshes { CUBE = "box" } node Start {} },
        "`CUBE` is the built-in unit cube",
    );
    one_error(
        quote! { axiom Start; meshes { A = "a" } meshes { B = "b" } node Start {} },
        "more than one `meshes` block",
    );
}

#[test]
fn axiom() {
    one_error(
        quote! { node Start {} },
        "generator `G` has no axiom; add `axiom Start;`",
    );
    one_error(
        quote! { axiom Strt; node Start {} },
        "unknown axiom `Strt`; did you mean `Start`?",
    );
    one_error(
        quote! { axiom Start; axiom Start; node Start {} },
        "more than one `axiom` line",
    );
}

#[test]
fn arrays() {
    one_error(
        quote! { axiom Start; node Start { children { a: [Start; 0] = 0.5 } } },
        "an array slot holds at least one child",
    );
    one_error(
        quote! { axiom Start; node Start { children { a: [Start; 1.5] = 0.5 } } },
        "expected an integer",
    );
}

#[test]
fn unreachable_nodes_are_errors() {
    one_error(
        quote! { axiom Start; node Start {} node Island { children { me: Island = 0.5 } } },
        "node `Island` cannot be reached from the axiom `Start`",
    );
    // Not reported when an unknown child name may be the missing edge.
    one_error(
        quote! { axiom Start; node Start { children { i: Islnd = 1.0 } } node Island {} },
        "unknown node `Islnd`",
    );
}

#[test]
fn sections() {
    one_error(
        quote! { axiom Start; node Start { param { a: f32 ~ uniform(0.0, 1.0) } } },
        "unknown section `param` (did you mean `params`?)",
    );
    one_error(
        quote! { axiom Start; node Start { derive {} } },
        "`derive` names the scope it works in",
    );
}

#[test]
fn attributes() {
    one_error(
        quote! { axiom Start; node Start { children { #[inline] a: Start = 0.5 } } },
        "only doc comments are allowed on child slots",
    );
    one_error(
        quote! { axiom Start; #[cfg(test)] node Start {} },
        "`cfg` and `cfg_attr` are not supported on the parts of a generator",
    );
}

#[test]
fn errors_are_reported_together() {
    let errs = errors(quote! {
        axiom Start;
        node Start {
            params { a: f64 ~ uniform(0.0, 1.0), b: f32 ~ uniform(1.0, 0.0) }
            children { x: Nope = 2.0 }
        }
        node Start {}
    });
    assert_eq!(errs.len(), 5, "{errs:#?}");
}

#[test]
fn parsing_recovers_at_entries_sections_and_items() {
    let errs = errors(quote! {
        axiom Start;
        node Start {
            params { a: f32 uniform(0.0, 1.0), b: f32 ~ uniform(0.0, 1.0) }
            children { c Start = 1.0, d: Start = 0.5 }
        }
        node Other oops
        node Third { derive(s) { } }
    });
    assert_eq!(errs.len(), 3, "{errs:#?}");
    assert!(errs[0].contains("expected `~`"), "{errs:#?}");
    assert!(errs[1].contains("expected `:`"), "{errs:#?}");
    assert!(
        errs[2].contains("expected `{` after `node Other`"),
        "{errs:#?}"
    );
}

#[test]
fn snake_case_names() {
    assert_eq!(snake_case("TopNext"), "top_next");
    assert_eq!(snake_case("Start"), "start");
    assert_eq!(snake_case("B1"), "b1");
    assert_eq!(snake_case("Top_Next"), "top_next");
}

#[test]
fn rule_fn_names_are_unique() {
    let cx = Ctxt::default();
    let input = parse_input(
        quote!(krate; G { axiom TopNext; node TopNext { children { a: Top_Next = 1.0 } } node Top_Next {} }),
        &cx,
    )
    .unwrap();
    let g = check(&input.generator, &cx);
    let names: Vec<String> = g.nodes.iter().map(|n| n.rule_fn.to_string()).collect();
    assert_eq!(names, ["__rule_top_next_0", "__rule_top_next_1"]);
}
