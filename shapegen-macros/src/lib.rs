//! The `generator!` procedural macro of shapegen. Use it through `shapegen::generator!`
//! (or `shapegen_runtime::generator!`), which passes this macro the path of the runtime
//! and documents the syntax.
//!
//! The macro is a pipeline of modules: `parse` (tokens to syntax tree) -> `check` (syntax
//! tree to the checked `model`, every mistake a spanned error) -> `layout` (gene layout)
//! -> `expand` (Rust items), or `fallback` when a check failed. Constant expressions are
//! evaluated by `consteval`; every stage records its errors in the collector of `ctxt`.
//! A module imports only from the stages before it (and from `model`, `consteval` and
//! `ctxt`, which import none of the others).

use proc_macro::TokenStream;

mod check;
mod consteval;
mod ctxt;
mod dist;
mod expand;
mod fallback;
mod layout;
mod model;
mod parse;

/// Expands a generator declaration. Called by the runtime's `generator!` wrapper as
/// `generator_impl! { $crate; <generator> }`.
#[doc(hidden)]
#[proc_macro]
pub fn generator_impl(input: TokenStream) -> TokenStream {
    generator(input.into()).into()
}

/// The expansion of `input` (`runtime path ; generator`), errors included.
fn generator(input: proc_macro2::TokenStream) -> proc_macro2::TokenStream {
    let cx = ctxt::Ctxt::default();
    let input = match parse::parse_input(input, &cx) {
        Ok(input) => input,
        Err(e) => {
            let mut errors = cx.finish();
            errors.push(e);
            return errors.iter().map(syn::Error::to_compile_error).collect();
        }
    };
    let model = check::check(&input.generator, &cx);
    let ex = expand::Expander::new(&model, &input.krate);
    let errors = cx.finish();
    if errors.is_empty()
        && let Some(out) = ex.expand()
    {
        return out;
    }
    fallback::expand(&ex, errors)
}

#[cfg(test)]
mod tests {
    use quote::quote;

    fn expand(body: proc_macro2::TokenStream) -> String {
        super::generator(quote!(::rt; #body)).to_string()
    }

    #[test]
    fn sound_grammar_expands_without_errors() {
        let out = expand(quote! {
            pub Spaceship {
                axiom Start;
                meshes { HULL = "hull" }
                node Start {
                    children { body: Body = 1.0 }
                    derive(s) { if let Some(body) = body { s.resize(body.size).derive(body); } }
                }
                node Body {
                    params { size: Vec3 ~ uniform([0.6; 3], [1.5; 3]), on: bool ~ bernoulli(0.5) }
                    children { next: Body = 1.0 / 3.0, lots: [Lot; 4] = 0.5 }
                    derive(s) { s.emit(HULL); }
                }
                node Lot { children { body: Body = 0.5 } }
            }
        });
        if std::env::var_os("SHOW_EXPANSION").is_some() {
            println!("{out}");
        }
        assert!(!out.contains("compile_error"), "{out}");
        for needle in [
            "pub struct Spaceship ;",
            "pub const HULL : :: rt :: __private :: MeshId = :: rt :: __private :: MeshId (1) ;",
            "# [repr (C)]",
            "pub size : :: rt :: __private :: Vec3",
            "probability : 0.33333334",
            "meshes : & [\"cube\" , \"hull\"]",
            "shape . derive_children (gene , 1)",
            "let lots : :: rt :: __private :: Slots < '__a , Lot , 4 > = :: rt :: __private :: Slots :: new (gene , 1) ;",
            "size_of :: < Body > () <= 16",
            "size_of :: < Start > () == 0",
        ] {
            assert!(out.contains(needle), "missing {needle:?} in\n{out}");
        }
    }

    #[test]
    fn mistakes_expand_to_errors_and_fallback_items() {
        let out = expand(quote! {
            pub G {
                axiom Start;
                node Start { params { a: f64 ~ uniform(0.0, 1.0), b: f32 ~ uniform(0.0, 1.0) } }
            }
        });
        assert!(out.contains("compile_error"), "{out}");
        assert!(out.contains("pub struct G ;"), "{out}");
        assert!(out.contains("pub b : :: core :: primitive :: f32"), "{out}");
        assert!(!out.contains("pub a :"), "{out}");
        assert!(out.contains("nodes : & []"), "{out}");
    }

    #[test]
    fn an_unreadable_header_gives_only_the_error() {
        let out = expand(quote!(pub { }));
        assert!(out.starts_with(":: core :: compile_error !"), "{out}");
    }
}
