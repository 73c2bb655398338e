//! The error collector of one expansion, shared by every stage: parsing and checking
//! record each mistake in a [`Ctxt`] and go on, so that the user sees all of them at once.

use std::cell::RefCell;

use quote::ToTokens;
use syn::Error;

/// Collects the errors of one expansion.
#[derive(Default)]
pub struct Ctxt {
    errors: RefCell<Vec<Error>>,
}

impl Ctxt {
    /// Records an error.
    pub fn push(&self, e: Error) {
        self.errors.borrow_mut().push(e);
    }

    /// Records an error spanning `tokens`.
    pub fn error(&self, tokens: impl ToTokens, msg: impl std::fmt::Display) {
        self.push(Error::new_spanned(tokens, msg));
    }

    /// Every error recorded, in order.
    pub fn finish(self) -> Vec<Error> {
        self.errors.into_inner()
    }
}
