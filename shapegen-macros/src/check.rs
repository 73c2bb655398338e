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

use proc_macro2::{Ident, Span, TokenStream};
use quote::{ToTokens, format_ident, quote};
use syn::{Expr, Type};

use crate::consteval::{eval_f32, eval_f64, eval_int, eval_vec, peel, to_f32};
use crate::ctxt::Ctxt;
use crate::model::{
    AngleUnit, Dist, Generator, HEADER_WORDS, Mesh, Node, Param, ParamType, Rule, Slot,
};
use crate::parse::{self, Item, Section, SlotTarget};

/// Tokens whose first and last spans are `start` and `end`, so that an error spanned on
/// them covers everything in between.
pub fn span_range(start: Span, end: Span) -> TokenStream {
    let a = Ident::new("a", start);
    let b = Ident::new("b", end);
    quote!(#a #b)
}

/// The supported types, for messages.
const TYPES: &str = "`f32`, `Vec2`, `Vec3`, `i32`, `u32` and `bool`";

/// Builds the model of `g`, reporting every mistake in `cx`.
pub fn check<'a>(g: &'a parse::Generator, cx: &Ctxt) -> Generator<'a> {
    // Nodes first: everything else refers to them by name.
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

    Generator {
        attrs: &g.attrs,
        vis: &g.vis,
        name: &g.name,
        axiom,
        meshes,
        nodes,
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
    let mut whole = !n.broken;
    let mut bindings_ok = true;
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
            whole = false;
            cx.error(
                keyword,
                format_args!(
                    "node `{}` has a second `{keyword}` section; put everything in one",
                    n.name
                ),
            );
        }
    }

    let scope = match &rule {
        Rule::Body { scope, .. } => Some(*scope),
        Rule::Default => None,
    };

    let mut params: Vec<Param<'a>> = Vec::new();
    for p in params_ast.into_iter().flatten() {
        if params.iter().any(|q| *q.name == p.name) {
            cx.error(
                &p.name,
                format_args!(
                    "parameter `{}` is declared twice in node `{}`; give each parameter its \
                     own name",
                    p.name, n.name
                ),
            );
            continue;
        }
        if let Some(scope) = scope.filter(|s| **s == p.name) {
            bindings_ok = false;
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
            whole = false;
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

    let mut slots: Vec<Slot<'a>> = Vec::new();
    for s in slots_ast.into_iter().flatten() {
        check_doc_only(&s.attrs, "child slots", cx);
        // A clashing slot stays in the model, so that the graph keeps its edge (and the
        // node it leads to is not reported unreachable); the bindings are marked bad.
        if slots.iter().any(|t| *t.name == s.name) {
            bindings_ok = false;
            cx.error(
                &s.name,
                format_args!(
                    "child slot `{}` is declared twice in node `{}`; give each slot its own \
                     name",
                    s.name, n.name
                ),
            );
        } else if params.iter().any(|p| *p.name == s.name) {
            bindings_ok = false;
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
            bindings_ok = false;
            cx.error(
                scope,
                format_args!(
                    "the rule's scope is named `{scope}`, like a child slot of node `{}`; \
                     rename one, both are bound in the rule's body",
                    n.name
                ),
            );
        }
        let node = s.target.node();
        let child = kinds.get(node.to_string().as_str()).copied();
        if child.is_none() {
            bindings_ok = false;
            cx.error(
                node,
                format_args!("unknown node `{node}`; {}", known_nodes(node, names)),
            );
        }
        let array = match &s.target {
            SlotTarget::Single(_) => None,
            SlotTarget::Array { node, len, .. } => {
                let n = check_array_len(node, len, cx);
                bindings_ok &= n.is_some();
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

    // Gene size must fit the genome's 32-bit word positions.
    let links: Option<u64> = slots.iter().map(|s| s.count().map(u64::from)).sum();
    let words: u64 = params
        .iter()
        .filter_map(|p| p.ty)
        .map(|t| u64::from(t.words()))
        .sum();
    if let Some(links) = links
        && u64::from(HEADER_WORDS) + links + words > u64::from(u32::MAX)
    {
        bindings_ok = false;
        cx.error(
            &n.name,
            format_args!(
                "node `{}` has {links} child links, more than a gene can hold; use fewer or \
                 shorter array slots",
                n.name
            ),
        );
    }

    Node {
        attrs: &n.attrs,
        name: &n.name,
        kind,
        rule_fn: format_ident!("__rule_{}", snake_case(&n.name.to_string())),
        params,
        slots,
        rule,
        whole,
        bindings_ok,
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

/// The distributions each type takes, for messages.
fn dists_of(ty: ParamType) -> &'static str {
    match ty {
        ParamType::F32 => "`uniform(lo, hi)`, `degrees(lo, hi)` or `radians(lo, hi)`",
        ParamType::Vec2 => "`uniform([x, y], [x, y])` (or `[v; 2]` bounds)",
        ParamType::Vec3 => "`uniform([x, y, z], [x, y, z])` (or `[v; 3]` bounds)",
        ParamType::I32 => "`uniform(lo..=hi)` or `uniform(lo..hi)`",
        ParamType::U32 => "`uniform(lo..=hi)`, `uniform(lo..hi)` or `weighted([w0, w1, ..])`",
        ParamType::Bool => "`bernoulli(p)`",
    }
}

fn check_dist(ty: ParamType, p: &parse::Param, cx: &Ctxt) -> Option<Dist> {
    let d = p.dist.to_string();
    let tn = ty.name();
    let an = if matches!(ty, ParamType::F32 | ParamType::I32) {
        "an"
    } else {
        "a"
    };
    let args: Vec<&Expr> = p.args.iter().collect();
    let call = span_range(p.dist.span(), p.paren.span.close());
    let applies = matches!(
        (ty, d.as_str()),
        (ParamType::F32, "uniform" | "degrees" | "radians")
            | (
                ParamType::Vec2 | ParamType::Vec3 | ParamType::I32,
                "uniform"
            )
            | (ParamType::U32, "uniform" | "weighted")
            | (ParamType::Bool, "bernoulli")
    );
    if !applies {
        let known =
            ["uniform", "degrees", "radians", "weighted", "bernoulli"].contains(&d.as_str());
        let what = if known {
            format!("`{d}` does not apply to {an} `{tn}` parameter")
        } else {
            format!("unknown distribution `{d}`")
        };
        cx.error(
            &p.dist,
            format_args!("{what}; {an} `{tn}` parameter takes {}", dists_of(ty)),
        );
        return None;
    }
    let arity = |n: usize, form: &str| -> bool {
        if args.len() == n {
            true
        } else {
            cx.error(
                &call,
                format_args!(
                    "`{d}` for {an} `{tn}` parameter takes {} argument{}: `{form}`",
                    n,
                    if n == 1 { "" } else { "s" },
                ),
            );
            false
        }
    };
    match (ty, d.as_str()) {
        (ParamType::F32, _) => {
            if !arity(2, &format!("{d}(lo, hi)")) {
                return None;
            }
            let lo = eval_f64(args[0]).map_err(|e| cx.push(e));
            let hi = eval_f64(args[1]).map_err(|e| cx.push(e));
            let (lo, hi) = (lo.ok()?, hi.ok()?);
            if lo > hi {
                cx.error(
                    quote!(#(#args),*),
                    format_args!(
                        "empty range: the lower bound {lo:?} is greater than the upper bound \
                         {hi:?}; write `{d}({hi:?}, {lo:?})`"
                    ),
                );
                return None;
            }
            let (lo32, hi32) = match d.as_str() {
                "degrees" => (lo.to_radians(), hi.to_radians()),
                _ => (lo, hi),
            };
            let lo32 = to_f32(lo32, args[0]).map_err(|e| cx.push(e));
            let hi32 = to_f32(hi32, args[1]).map_err(|e| cx.push(e));
            let (lo32, hi32) = (lo32.ok()?, hi32.ok()?);
            Some(match d.as_str() {
                "uniform" => Dist::Uniform { lo: lo32, hi: hi32 },
                unit => Dist::Angle {
                    lo: lo32,
                    hi: hi32,
                    unit: if unit == "degrees" {
                        AngleUnit::Degrees
                    } else {
                        AngleUnit::Radians
                    },
                    written: (lo, hi),
                },
            })
        }
        (ParamType::Vec2 | ParamType::Vec3, _) => {
            let n = ty.words() as usize;
            let form = if n == 2 {
                "uniform([x, y], [x, y])"
            } else {
                "uniform([x, y, z], [x, y, z])"
            };
            if !arity(2, form) {
                return None;
            }
            if !args
                .iter()
                .any(|a| matches!(peel(a), Expr::Array(_) | Expr::Repeat(_)))
            {
                cx.error(
                    quote!(#(#args),*),
                    format_args!(
                        "the bounds of {an} `{tn}` parameter are arrays, one number per \
                         component: `{form}`, or `[v; {n}]` for equal components"
                    ),
                );
                return None;
            }
            let lo = eval_vec(args[0], n, tn).map_err(|e| cx.push(e));
            let hi = eval_vec(args[1], n, tn).map_err(|e| cx.push(e));
            let (lo, hi) = (lo.ok()?, hi.ok()?);
            let mut ok = true;
            let mut lo32 = [0.0f32; 3];
            let mut hi32 = [0.0f32; 3];
            // Empty components, grouped by the bounds they were written as, so that
            // `[1.5; 3]` over `[0.6; 3]` is one mistake.
            let mut empty: Vec<(usize, usize, Vec<&str>)> = Vec::new();
            for (i, (l, h)) in lo.iter().zip(&hi).enumerate() {
                let axis = ["x", "y", "z"][i];
                if l.value > h.value {
                    ok = false;
                    let same = |&(a, b, _): &(usize, usize, Vec<&str>)| {
                        std::ptr::eq(lo[a].expr, l.expr) && std::ptr::eq(hi[b].expr, h.expr)
                    };
                    match empty.iter_mut().find(|e| same(e)) {
                        Some(e) => e.2.push(axis),
                        None => empty.push((i, i, vec![axis])),
                    }
                    continue;
                }
                match (to_f32(l.value, l.expr), to_f32(h.value, h.expr)) {
                    (Ok(a), Ok(b)) => (lo32[i], hi32[i]) = (a, b),
                    (a, b) => {
                        ok = false;
                        a.err().into_iter().chain(b.err()).for_each(|e| cx.push(e));
                    }
                }
            }
            for (i, _, axes) in empty {
                let (l, h) = (lo[i].value, hi[i].value);
                let which = match axes.as_slice() {
                    [one] => format!("component {one}"),
                    many => format!("components {}", many.join(", ")),
                };
                cx.error(
                    hi[i].expr,
                    format_args!(
                        "empty range in {which}: the upper bound {h:?} is below the lower \
                         bound {l:?}; each component needs lower <= upper"
                    ),
                );
            }
            ok.then(|| {
                if n == 2 {
                    Dist::UniformVec2 {
                        lo: [lo32[0], lo32[1]],
                        hi: [hi32[0], hi32[1]],
                    }
                } else {
                    Dist::UniformVec3 { lo: lo32, hi: hi32 }
                }
            })
        }
        (ParamType::I32 | ParamType::U32, "uniform") => {
            let range = match args.as_slice() {
                [arg] => match peel(arg) {
                    Expr::Range(r) => Some(r),
                    _ => None,
                },
                _ => None,
            };
            let Some(r) = range else {
                cx.error(
                    &call,
                    format_args!(
                        "{an} `{tn}` parameter takes a range: `uniform(lo..=hi)` (both ends \
                         included) or `uniform(lo..hi)`"
                    ),
                );
                return None;
            };
            let (Some(start), Some(end)) = (&r.start, &r.end) else {
                cx.error(
                    r,
                    "the range needs both ends: `uniform(lo..=hi)` or `uniform(lo..hi)`",
                );
                return None;
            };
            let a = eval_int(start).map_err(|e| cx.push(e));
            let b = eval_int(end).map_err(|e| cx.push(e));
            let (a, b) = (a.ok()?, b.ok()?);
            let closed = matches!(r.limits, syn::RangeLimits::Closed(_));
            let (lo, hi) = if closed { (a, b) } else { (a, b - 1) };
            if lo > hi {
                let msg = if closed {
                    format!("the range {a}..={b} is empty: {b} is below {a}; write `{b}..={a}`")
                } else if a == b {
                    format!(
                        "the range {a}..{b} is empty (`..` leaves out its upper end); write \
                         `{a}..={a}` for the single value {a}"
                    )
                } else {
                    format!("the range {a}..{b} is empty: it needs {a} < {b}")
                };
                cx.error(r, msg);
                return None;
            }
            let (min, max) = if ty == ParamType::I32 {
                (i128::from(i32::MIN), i128::from(i32::MAX))
            } else {
                (0, i128::from(u32::MAX))
            };
            let mut ok = true;
            for (v, e) in [(lo, start), (hi, end)] {
                if v < min || v > max {
                    ok = false;
                    cx.error(
                        e,
                        format_args!(
                            "{v} does not fit {an} `{tn}` parameter, whose values lie in \
                             {min}..={max}"
                        ),
                    );
                }
            }
            if !ok {
                return None;
            }
            Some(if ty == ParamType::I32 {
                Dist::Int {
                    lo: lo as i32,
                    hi: hi as i32,
                }
            } else {
                Dist::Index {
                    lo: lo as u32,
                    hi: hi as u32,
                }
            })
        }
        (ParamType::U32, _) => {
            if !arity(1, "weighted([w0, w1, ..])") {
                return None;
            }
            check_weights(args[0], cx).map(|weights| Dist::Weighted { weights })
        }
        (ParamType::Bool, _) => {
            if !arity(1, "bernoulli(p)") {
                return None;
            }
            match eval_f32(args[0]) {
                Ok(p) if (0.0..=1.0).contains(&p) => Some(Dist::Bernoulli { p }),
                Ok(p) => {
                    cx.error(
                        args[0],
                        format_args!(
                            "probability {p:?} is outside [0, 1]; `bernoulli(p)` is `true` with \
                             probability p, between 0.0 and 1.0"
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
        _ => None,
    }
}

fn check_weights(arg: &Expr, cx: &Ctxt) -> Option<Vec<f32>> {
    let exprs: Vec<&Expr> = match peel(arg) {
        Expr::Array(a) => a.elems.iter().collect(),
        Expr::Repeat(r) => match eval_int(&r.len) {
            Ok(n) if (0..=1 << 16).contains(&n) => vec![&*r.expr; n as usize],
            Ok(n) => {
                cx.error(&r.len, format_args!("{n} weights are too many or too few"));
                return None;
            }
            Err(e) => {
                cx.push(e);
                return None;
            }
        },
        _ => {
            cx.error(
                arg,
                "`weighted` takes an array of weights: `weighted([1.0, 2.0, 0.5])`; index i is \
                 drawn with probability w_i / sum(w)",
            );
            return None;
        }
    };
    if exprs.is_empty() {
        cx.error(
            arg,
            "`weighted` needs at least one weight: `weighted([1.0, 2.0])`",
        );
        return None;
    }
    let mut ok = true;
    let mut weights = Vec::with_capacity(exprs.len());
    for e in &exprs {
        match eval_f32(e) {
            Ok(w) if w < 0.0 => {
                ok = false;
                cx.error(
                    e,
                    format_args!("weight {w:?} is negative; weights are 0 or more"),
                );
            }
            Ok(w) => weights.push(w),
            Err(err) => {
                ok = false;
                cx.push(err);
            }
        }
    }
    if ok && weights.iter().all(|&w| w == 0.0) {
        cx.error(
            arg,
            "every weight is zero; at least one must be positive, or no index can be drawn",
        );
        return None;
    }
    ok.then_some(weights)
}

#[cfg(test)]
mod tests;
