//! The `generator!` procedural macro of shapegen. Use it through `shapegen::generator!`
//! (or `shapegen_runtime::generator!`), which passes this macro the path of the runtime
//! and documents the syntax.
//!
//! The macro is a pipeline: [`parse`] (tokens to syntax tree) -> [`check`] (syntax tree
//! to the checked [`model`], every mistake a spanned error) -> [`layout`] (gene layout)
//! -> [`expand`] (Rust items), or [`fallback`] when a check failed. Constant expressions
//! are evaluated by [`consteval`].

use proc_macro::TokenStream;

mod check;
mod consteval;
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
    let cx = check::Ctxt::default();
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
