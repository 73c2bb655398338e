//! The `generator!` procedural macro of shapegen. Use it through `shapegen::generator!`
//! (or `shapegen_runtime::generator!`), which passes this macro the path of the runtime.

use proc_macro::TokenStream;

/// Expands a grammar declaration. Called by the runtime's `generator!` wrapper as
/// `generator_impl! { $crate; <grammar> }`.
#[doc(hidden)]
#[proc_macro]
pub fn generator_impl(input: TokenStream) -> TokenStream {
    let _ = input;
    TokenStream::new()
}
