//! Checks: the syntax tree into the [model](crate::model), every mistake reported as a
//! `syn::Error` on the user's own tokens and collected in a [`Ctxt`](crate::ctxt::Ctxt), so that all of them
//! are shown at once.
//!
//! What is checked: node, parameter, slot and mesh names are unique (and a parameter and a
//! slot of one node, or either and the rule's scope, do not share a name); each node has
//! each section at most once; there is exactly one `axiom` line and it names a node;
//! child slots name declared nodes; probabilities lie in `[0, 1]`; array slots hold at
//! least one child; parameter types are supported and their distributions fit them, with
//! non-empty ranges and valid weights; every node can be reached from the axiom.

use std::collections::{HashMap, HashSet, VecDeque};

use proc_macro2::Ident;
use quote::{ToTokens, format_ident, quote};
use syn::{Expr, Type};

use crate::consteval::{eval_f32, eval_int};
use crate::ctxt::Ctxt;
use crate::dist::check_dist;
use crate::model::{Generator, HEADER_WORDS, Mesh, Node, Param, ParamType, Rule, Slot};
use crate::parse::{self, Item, Section, SlotTarget};

/// The supported types, for messages.
const TYPES: &str = "`f32`, `Vec2`, `Vec3`, `i32`, `u32` and `bool`";

/// Builds the model of `g`, reporting every mistake in `cx`.
pub fn check<'a>(g: &'a parse::Generator, cx: &Ctxt) -> Generator<'a> {
    // Nodes first: everything else refers to them by name.
    let (node_asts, any_dropped) = distinct_nodes(g, cx);
    check_no_cfg(
        &g.attrs,
        "a generator; put the `generator!` in a `#[cfg(..)]` module instead",
        cx,
    );
    let names: Vec<String> = node_asts.iter().map(|n| n.name.to_string()).collect();
    let kinds: HashMap<&str, u32> = names
        .iter()
        .enumerate()
        .map(|(i, n)| (n.as_str(), i as u32))
        .collect();

    let axiom = check_axiom(g, &names, &kinds, cx);
    let meshes = check_meshes(g, cx);

    let mut nodes: Vec<Node<'a>> = node_asts
        .iter()
        .enumerate()
        .map(|(kind, n)| check_node(n, kind as u32, &names, &kinds, cx))
        .collect();
    name_rule_fns(&mut nodes);

    // Reachability, only when the graph is fully known: an unknown child name or a
    // dropped node already has its error, and the nodes behind it would only look
    // unreachable.
    let one_children_section = |n: &&parse::Node| {
        let children = n.sections.iter();
        children
            .filter(|s| matches!(s, Section::Children { .. }))
            .count()
            <= 1
    };
    let graph_known = !any_dropped
        && node_asts
            .iter()
            .all(|n| !n.broken && one_children_section(n))
        && nodes
            .iter()
            .all(|n| n.slots.iter().all(|s| s.child.is_some()));
    if let (Some(axiom), true) = (axiom, graph_known) {
        report_unreachable(&nodes, axiom, &names, cx);
    }

    Generator {
        attrs: &g.attrs,
        vis: &g.vis,
        name: &g.name,
        axiom,
        meshes,
        nodes,
    }
}

/// The nodes of `g`, each name once: a node named like the generator, or like an
/// earlier node, is reported and dropped (the `bool` says whether any was).
fn distinct_nodes<'a>(g: &'a parse::Generator, cx: &Ctxt) -> (Vec<&'a parse::Node>, bool) {
    let mut node_asts: Vec<&parse::Node> = Vec::new();
    let mut any_dropped = false;
    for item in &g.items {
        let Item::Node(n) = item else { continue };
        if n.name == g.name {
            any_dropped = true;
            cx.error(
                &n.name,
                format_args!(
                    "node `{0}` has the same name as its generator; rename one (node `{0}` \
                     names a parameter struct and generator `{0}` a unit struct, in the same \
                     module)",
                    n.name
                ),
            );
        } else if node_asts.iter().any(|m| m.name == n.name) {
            any_dropped = true;
            cx.error(
                &n.name,
                format_args!(
                    "node `{}` is declared twice; give each node its own name",
                    n.name
                ),
            );
        } else {
            node_asts.push(n);
        }
    }
    (node_asts, any_dropped)
}

/// Reports every node that no chain of children leads to from `axiom`.
fn report_unreachable(nodes: &[Node], axiom: u32, names: &[String], cx: &Ctxt) {
    let mut seen = vec![false; nodes.len()];
    let mut queue = VecDeque::from([axiom]);
    seen[axiom as usize] = true;
    while let Some(k) = queue.pop_front() {
        for child in nodes[k as usize].slots.iter().filter_map(|s| s.child) {
            if !std::mem::replace(&mut seen[child as usize], true) {
                queue.push_back(child);
            }
        }
    }
    for (n, _) in nodes.iter().zip(&seen).filter(|(_, seen)| !**seen) {
        cx.error(
            n.name,
            format_args!(
                "node `{}` cannot be reached from the axiom `{}`: no chain of children \
                 leads to it, so it can never appear in a genome; make it a child of a \
                 reachable node, or remove it",
                n.name, names[axiom as usize]
            ),
        );
    }
}

fn check_axiom(
    g: &parse::Generator,
    names: &[String],
    kinds: &HashMap<&str, u32>,
    cx: &Ctxt,
) -> Option<u32> {
    let mut axioms = g.items.iter().filter_map(|item| match item {
        Item::Axiom { keyword, node } => Some((keyword, node)),
        _ => None,
    });
    let Some((_, axiom)) = axioms.next() else {
        let example = names.first().map_or("Start", String::as_str);
        cx.error(
            &g.name,
            format_args!(
                "generator `{}` has no axiom; add `axiom {example};` naming the node its \
                 derivations start from",
                g.name
            ),
        );
        return None;
    };
    for (keyword, node) in axioms {
        cx.error(
            quote!(#keyword #node),
            format_args!(
                "more than one `axiom` line; a generator has one axiom, keep only `axiom \
                 {axiom};` or this one"
            ),
        );
    }
    match kinds.get(axiom.to_string().as_str()) {
        Some(&k) => Some(k),
        None => {
            cx.error(
                axiom,
                format_args!("unknown axiom `{axiom}`; {}", known_nodes(axiom, names)),
            );
            None
        }
    }
}

fn check_meshes<'a>(g: &'a parse::Generator, cx: &Ctxt) -> Vec<Mesh<'a>> {
    let mut blocks = g.items.iter().filter_map(|item| match item {
        Item::Meshes { keyword, meshes } => Some((keyword, meshes)),
        _ => None,
    });
    let mut out: Vec<Mesh<'a>> = Vec::new();
    let Some((_, entries)) = blocks.next() else {
        return out;
    };
    for (keyword, _) in blocks {
        cx.error(
            keyword,
            "more than one `meshes` block; list every mesh in the first one",
        );
    }
    for m in entries {
        check_no_cfg(&m.attrs, PARTS_CFG, cx);
        let file = m.file.value();
        if m.name == "CUBE" {
            cx.error(
                &m.name,
                "`CUBE` is the built-in unit cube, mesh 0 of every generator; name this mesh \
                 otherwise",
            );
        } else if file == "cube" {
            cx.error(
                &m.file,
                "\"cube\" is the built-in unit cube, mesh 0 of every generator (`CUBE`); it \
                 needs no declaration",
            );
        } else if file.is_empty() {
            cx.error(&m.file, "a mesh's name cannot be empty");
        } else if m.name == g.name {
            cx.error(
                &m.name,
                format_args!(
                    "mesh `{}` has the same name as its generator; rename one",
                    m.name
                ),
            );
        } else if let Some(first) = out.iter().find(|o| *o.name == m.name) {
            cx.error(
                &m.name,
                format_args!(
                    "mesh constant `{}` is declared twice (first for \"{}\"); give each \
                     mesh its own constant",
                    m.name, first.file
                ),
            );
        } else if let Some(first) = out.iter().find(|o| o.file == file) {
            cx.error(
                &m.file,
                format_args!(
                    "mesh \"{file}\" is declared twice (first as `{}`); declare each mesh \
                     once and use its constant everywhere",
                    first.name
                ),
            );
        } else {
            out.push(Mesh {
                attrs: &m.attrs,
                name: &m.name,
                file,
                id: out.len() as u32 + 1,
            });
        }
    }
    out
}

fn check_node<'a>(
    n: &'a parse::Node,
    kind: u32,
    names: &[String],
    kinds: &HashMap<&str, u32>,
    cx: &Ctxt,
) -> Node<'a> {
    check_no_cfg(&n.attrs, PARTS_CFG, cx);
    let mut check = NodeCheck {
        n,
        cx,
        whole: !n.broken,
        bindings_ok: true,
    };
    let (params_ast, slots_ast, rule) = check.sections();
    let scope = match &rule {
        Rule::Body { scope, .. } => Some(*scope),
        Rule::Default => None,
    };
    let params = check.params(params_ast, scope);
    let slots = check.slots(slots_ast, &params, scope, names, kinds);
    check.gene_size(&params, &slots);
    Node {
        attrs: &n.attrs,
        name: &n.name,
        kind,
        rule_fn: format_ident!("__rule_{}", snake_case(&n.name.to_string())),
        params,
        slots,
        rule,
        whole: check.whole,
        bindings_ok: check.bindings_ok,
    }
}

/// The checking of one node: what it found so far, whether the node is whole (its rule
/// can be generated) and whether its bindings are sound.
struct NodeCheck<'a, 'c> {
    n: &'a parse::Node,
    cx: &'c Ctxt,
    whole: bool,
    bindings_ok: bool,
}

/// A node's parameter and slot declarations, as parsed.
type ParamsAst<'a> = Option<&'a Vec<parse::Param>>;
type SlotsAst<'a> = Option<&'a Vec<parse::Slot>>;

impl<'a> NodeCheck<'a, '_> {
    /// The node's sections: its parameters, slots and rule, each the first of its kind
    /// (a second is reported).
    fn sections(&mut self) -> (ParamsAst<'a>, SlotsAst<'a>, Rule<'a>) {
        let n = self.n;
        let mut rule = Rule::Default;
        let (mut params_ast, mut slots_ast) = (None, None);
        let (mut params_seen, mut children_seen, mut derive_seen) = (false, false, false);
        for section in &n.sections {
            let (keyword, seen) = match section {
                Section::Params { keyword, params } => {
                    params_ast.get_or_insert(params);
                    (keyword, &mut params_seen)
                }
                Section::Children { keyword, slots } => {
                    slots_ast.get_or_insert(slots);
                    (keyword, &mut children_seen)
                }
                Section::Derive {
                    keyword,
                    mutability,
                    scope,
                    body,
                } => {
                    if !derive_seen {
                        rule = Rule::Body {
                            mutability: mutability.as_ref(),
                            scope,
                            body,
                        };
                    }
                    (keyword, &mut derive_seen)
                }
            };
            // Keep the first of a duplicated section.
            if std::mem::replace(seen, true) {
                self.whole = false;
                self.cx.error(
                    keyword,
                    format_args!(
                        "node `{}` has a second `{keyword}` section; put everything in one",
                        n.name
                    ),
                );
            }
        }
        (params_ast, slots_ast, rule)
    }

    /// The node's parameters: names unique and apart from the rule's `scope`, types
    /// supported, distributions fitting them.
    fn params(&mut self, params_ast: ParamsAst<'a>, scope: Option<&Ident>) -> Vec<Param<'a>> {
        let (n, cx) = (self.n, self.cx);
        let mut params: Vec<Param<'a>> = Vec::new();
        for p in params_ast.into_iter().flatten() {
            if params.iter().any(|q| *q.name == p.name) {
                cx.error(
                    &p.name,
                    format_args!(
                        "parameter `{}` is declared twice in node `{}`; give each parameter \
                         its own name",
                        p.name, n.name
                    ),
                );
                continue;
            }
            if let Some(scope) = scope.filter(|s| **s == p.name) {
                self.bindings_ok = false;
                cx.error(
                    scope,
                    format_args!(
                        "the rule's scope is named `{scope}`, like a parameter of node `{}`; \
                         rename one, both are bound in the rule's body",
                        n.name
                    ),
                );
            }
            check_no_cfg(&p.attrs, PARTS_CFG, cx);
            let ty = param_type(&p.ty);
            if ty.is_none() {
                self.whole = false;
                let written = p.ty.to_token_stream().to_string();
                cx.error(
                    &p.ty,
                    format_args!(
                        "unsupported parameter type `{written}`; the supported types are {TYPES}"
                    ),
                );
            }
            let dist = ty.and_then(|ty| check_dist(ty, p, cx));
            params.push(Param {
                attrs: &p.attrs,
                name: &p.name,
                ty,
                dist,
            });
        }
        params
    }

    /// The node's child slots: names unique and apart from its `params` and the rule's
    /// `scope`, naming known nodes, array lengths and probabilities valid.
    fn slots(
        &mut self,
        slots_ast: SlotsAst<'a>,
        params: &[Param<'a>],
        scope: Option<&Ident>,
        names: &[String],
        kinds: &HashMap<&str, u32>,
    ) -> Vec<Slot<'a>> {
        let cx = self.cx;
        let mut slots: Vec<Slot<'a>> = Vec::new();
        for s in slots_ast.into_iter().flatten() {
            check_doc_only(&s.attrs, "child slots", cx);
            // A clashing slot stays in the model, so that the graph keeps its edge (and
            // the node it leads to is not reported unreachable); the bindings are marked
            // bad.
            self.slot_name(s, &slots, params, scope);
            let node = s.target.node();
            let child = kinds.get(node.to_string().as_str()).copied();
            if child.is_none() {
                self.bindings_ok = false;
                cx.error(
                    node,
                    format_args!("unknown node `{node}`; {}", known_nodes(node, names)),
                );
            }
            let array = match &s.target {
                SlotTarget::Single(_) => None,
                SlotTarget::Array { node, len, .. } => {
                    let n = check_array_len(node, len, cx);
                    self.bindings_ok &= n.is_some();
                    Some(n)
                }
            };
            let probability = check_probability(&s.probability, cx);
            slots.push(Slot {
                name: &s.name,
                node,
                child,
                array,
                probability,
            });
        }
        slots
    }

    /// Reports a slot `s` whose name another slot, a parameter or the rule's scope has.
    fn slot_name(
        &mut self,
        s: &parse::Slot,
        slots: &[Slot<'a>],
        params: &[Param<'a>],
        scope: Option<&Ident>,
    ) {
        let (n, cx) = (self.n, self.cx);
        if slots.iter().any(|t| *t.name == s.name) {
            self.bindings_ok = false;
            cx.error(
                &s.name,
                format_args!(
                    "child slot `{}` is declared twice in node `{}`; give each slot its own \
                     name",
                    s.name, n.name
                ),
            );
        } else if params.iter().any(|p| *p.name == s.name) {
            self.bindings_ok = false;
            cx.error(
                &s.name,
                format_args!(
                    "node `{}` has a parameter and a child slot both named `{}`; rename one, \
                     both are bound by name in the rule's body",
                    n.name, s.name
                ),
            );
        }
        if let Some(scope) = scope.filter(|sc| **sc == s.name) {
            self.bindings_ok = false;
            cx.error(
                scope,
                format_args!(
                    "the rule's scope is named `{scope}`, like a child slot of node `{}`; \
                     rename one, both are bound in the rule's body",
                    n.name
                ),
            );
        }
    }

    /// Reports a gene too large for the genome's 32-bit word positions.
    fn gene_size(&mut self, params: &[Param<'a>], slots: &[Slot<'a>]) {
        let n = self.n;
        let links: Option<u64> = slots.iter().map(|s| s.count().map(u64::from)).sum();
        let words: u64 = params
            .iter()
            .filter_map(|p| p.ty)
            .map(|t| u64::from(t.words()))
            .sum();
        if let Some(links) = links
            && u64::from(HEADER_WORDS) + links + words > u64::from(u32::MAX)
        {
            self.bindings_ok = false;
            self.cx.error(
                &n.name,
                format_args!(
                    "node `{}` has {links} child links, more than a gene can hold; use fewer \
                     or shorter array slots",
                    n.name
                ),
            );
        }
    }
}

/// Makes rule function names unique: a clash of snake-case names (`TopNext`, `Top_Next`)
/// is resolved by appending the kind.
fn name_rule_fns(nodes: &mut [Node]) {
    let mut seen = HashSet::new();
    let clashes: HashSet<String> = nodes
        .iter()
        .map(|n| n.rule_fn.to_string())
        .filter(|name| !seen.insert(name.clone()))
        .collect();
    for n in nodes {
        if clashes.contains(&n.rule_fn.to_string()) {
            n.rule_fn = format_ident!("{}_{}", n.rule_fn, n.kind);
        }
    }
}

/// `TopNext` -> `top_next`.
pub fn snake_case(name: &str) -> String {
    let name = name.strip_prefix("r#").unwrap_or(name);
    let mut out = String::new();
    let mut prev_lower = false;
    for c in name.chars() {
        if c.is_uppercase() {
            if prev_lower {
                out.push('_');
            }
            out.extend(c.to_lowercase());
            prev_lower = false;
        } else {
            prev_lower = c != '_';
            out.push(c);
        }
    }
    out
}

/// Reports the attributes other than doc comments in `attrs`.
fn check_doc_only(attrs: &[syn::Attribute], what: &str, cx: &Ctxt) {
    for a in attrs.iter().filter(|a| !a.path().is_ident("doc")) {
        cx.error(
            a,
            format_args!(
                "only doc comments are allowed on {what}; this attribute has no item to go on"
            ),
        );
    }
}

/// What `check_no_cfg` says about nodes, parameters and meshes.
const PARTS_CFG: &str = "the parts of a generator; its graph always lists every node, \
                         parameter and mesh, so declare one generator per variant";

/// Reports conditional compilation on `attrs`: a node or parameter that may vanish would
/// leave the generator graph referring to it.
fn check_no_cfg(attrs: &[syn::Attribute], what: &str, cx: &Ctxt) {
    for a in attrs
        .iter()
        .filter(|a| a.path().is_ident("cfg") || a.path().is_ident("cfg_attr"))
    {
        cx.error(
            a,
            format_args!("`cfg` and `cfg_attr` are not supported on {what}"),
        );
    }
}

fn param_type(ty: &Type) -> Option<ParamType> {
    match ty {
        Type::Path(p) if p.qself.is_none() && p.path.leading_colon.is_none() => {
            match p.path.segments.iter().collect::<Vec<_>>().as_slice() {
                [seg] if seg.arguments.is_none() => ParamType::from_name(&seg.ident.to_string()),
                _ => None,
            }
        }
        Type::Group(g) => param_type(&g.elem),
        Type::Paren(p) => param_type(&p.elem),
        _ => None,
    }
}

/// "the declared nodes are `A`, `B`", with a suggestion when a name is close to `name`.
fn known_nodes(name: &Ident, names: &[String]) -> String {
    if names.is_empty() {
        return format!("the generator declares no nodes; add `node {name} {{ .. }}`");
    }
    let name = name.to_string();
    let list = names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ");
    let close = names
        .iter()
        .map(|n| (edit_distance(&name.to_lowercase(), &n.to_lowercase()), n))
        .filter(|(d, n)| *d <= 2.max(n.len() / 3))
        .min_by_key(|(d, _)| *d);
    match close {
        Some((_, n)) => format!("did you mean `{n}`? The declared nodes are {list}"),
        None => format!("the declared nodes are {list}"),
    }
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

fn check_probability(expr: &Expr, cx: &Ctxt) -> Option<f32> {
    match eval_f32(expr) {
        Ok(p) if (0.0..=1.0).contains(&p) => Some(p),
        Ok(p) => {
            cx.error(
                expr,
                format_args!(
                    "probability {p:?} is outside [0, 1]; a child's probability is the chance \
                     that it appears, between 0.0 and 1.0"
                ),
            );
            None
        }
        Err(e) => {
            cx.push(e);
            None
        }
    }
}

fn check_array_len(node: &Ident, len: &Expr, cx: &Ctxt) -> Option<u32> {
    match eval_int(len) {
        Ok(0) => cx.error(
            len,
            format_args!(
                "an array slot holds at least one child: `[{node}; 0]` has no room; give it a \
                 length of 1 or more, or remove the slot"
            ),
        ),
        Ok(n) if n < 0 => cx.error(
            len,
            format_args!("an array slot's length cannot be negative, found {n}"),
        ),
        Ok(n) => match u32::try_from(n) {
            Ok(n) => return Some(n),
            Err(_) => cx.error(
                len,
                format_args!(
                    "array slot of {n} children is too long; at most {}",
                    u32::MAX
                ),
            ),
        },
        Err(e) => cx.push(e),
    }
    None
}

#[cfg(test)]
mod tests;
