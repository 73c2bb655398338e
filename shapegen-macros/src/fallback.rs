//! The expansion of a generator with mistakes: besides the errors, the items the rest of
//! the user's crate refers to, so that the user sees the macro's errors and not a cascade
//! of unknown names (the approach of `thiserror`'s fallback).
//!
//! Emitted: the grammar struct with a stub `Grammar` impl (an empty graph, no rules), the
//! mesh constants that are right, every node's parameter struct with the parameters whose
//! type is known and its `NodeParams` and `NodeRule` impls (a rule that does nothing
//! where the node's is not emitted), and the rule functions of the nodes whose
//! bindings are all known (so the compiler still checks those bodies, and the user's
//! imports they use stay used).

use proc_macro2::TokenStream;
use quote::quote;
use syn::Error;

use crate::expand::Expander;
use crate::layout::{self, NodeLayout};
use crate::model::{Node, Param, Rule};

/// The errors, then the fallback items.
pub fn expand(ex: &Expander, errors: Vec<Error>) -> TokenStream {
    let g = ex.g;
    let name = g.name;
    let mut out: TokenStream = errors.into_iter().map(|e| e.to_compile_error()).collect();
    out.extend(ex.grammar_struct());
    out.extend(ex.mesh_consts());
    let mut impls = TokenStream::new();
    let mut rules = TokenStream::new();
    for node in &g.nodes {
        let params: Vec<&Param> = node.params.iter().filter(|p| p.ty.is_some()).collect();
        out.extend(ex.param_struct(node, &params));
        let links = layout::links(node).unwrap_or(0);
        impls.extend(ex.node_params_impl(node, &params, links));
        let layout = rule_layout(g.nodes.as_slice(), node);
        if let Some(layout) = &layout {
            rules.extend(ex.rule_fn(node, layout));
        }
        impls.extend(ex.node_rule_impl(node, layout.is_some()));
    }
    let grammar_impl = ex.stub_grammar_impl();
    out.extend(quote! {
        impl #name {
            #rules
        }
        const _: () = {
            #impls
            #grammar_impl
        };
    });
    out
}

/// The layout to emit `node`'s rule body with, when every name its body may use is known:
/// its parameters and slots, and the fields of the children its slots hold.
fn rule_layout(nodes: &[Node], node: &Node) -> Option<NodeLayout> {
    let children_whole = node
        .slots
        .iter()
        .all(|s| s.child.is_some_and(|c| nodes[c as usize].whole));
    let emit =
        matches!(node.rule, Rule::Body { .. }) && node.whole && node.bindings_ok && children_whole;
    emit.then(|| layout::node_layout(node)).flatten()
}
