//! Parsing: the macro's tokens into a syntax tree, recovering from mistakes where it can.
//!
//! The accepted syntax (`*` repeats, `?` is optional, `,*` is a comma-separated list that
//! may end with a comma):
//!
//! ```text
//! Input     := RuntimePath ";" Generator          // from the runtime's wrapper
//! Generator := OuterAttr* Visibility Ident "{" Item* "}"
//! Item      := "axiom" Ident ";"
//!            | "meshes" "{" (OuterAttr* Ident "=" LitStr),* "}"
//!            | OuterAttr* "node" Ident "{" Section* "}"
//! Section   := "params" "{" Param,* "}"
//!            | "children" "{" Slot,* "}"
//!            | "derive" "(" "mut"? Ident ")" "{" RustStatements "}"
//! Param     := OuterAttr* Ident ":" Type "~" Ident "(" Expr,* ")"
//! Slot      := OuterAttr* Ident ":" (Ident | "[" Ident ";" Expr "]") "=" Expr
//! ```
//!
//! Parsing recovers at every list entry, section and item: a mistake is recorded in the
//! [`Ctxt`] and parsing resumes at the next `,`, section keyword or item keyword, so
//! several syntax errors are reported together and the rest of the grammar still reaches
//! the checks and the fallback expansion. Meaning (types, distributions, constants, node
//! names) is left to [`check`](crate::check).

use proc_macro2::{Delimiter, Group, Ident, TokenStream, TokenTree};
use syn::ext::IdentExt;
use syn::parse::discouraged::Speculative;
use syn::parse::{Parse, ParseStream, Parser};
use syn::punctuated::Punctuated;
use syn::{
    Attribute, Error, Expr, LitStr, Result, Token, Type, Visibility, braced, bracketed,
    parenthesized, token,
};

use crate::ctxt::Ctxt;

mod kw {
    syn::custom_keyword!(axiom);
    syn::custom_keyword!(meshes);
    syn::custom_keyword!(node);
    syn::custom_keyword!(params);
    syn::custom_keyword!(children);
    syn::custom_keyword!(derive);
}

/// The whole input of `generator_impl!`.
pub struct Input {
    /// The runtime's path, as the wrapper passed it (`$crate`).
    pub krate: TokenStream,
    /// The generator declaration.
    pub generator: Generator,
}

/// A generator declaration.
pub struct Generator {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub items: Vec<Item>,
}

/// An item of a generator's body.
pub enum Item {
    /// `axiom Name;`
    Axiom { keyword: Ident, node: Ident },
    /// `meshes { NAME = "file", .. }`
    Meshes { keyword: Ident, meshes: Vec<Mesh> },
    /// `node Name { .. }`
    Node(Node),
}

/// `NAME = "file"` in a `meshes` block.
pub struct Mesh {
    pub attrs: Vec<Attribute>,
    pub name: Ident,
    pub file: LitStr,
}

/// `node Name { sections }`.
pub struct Node {
    pub attrs: Vec<Attribute>,
    pub name: Ident,
    pub sections: Vec<Section>,
    /// Whether some part of the node's body failed to parse (and was skipped).
    pub broken: bool,
}

/// A section of a node.
pub enum Section {
    /// `params { .. }`
    Params { keyword: Ident, params: Vec<Param> },
    /// `children { .. }`
    Children { keyword: Ident, slots: Vec<Slot> },
    /// `derive(scope) { body }`
    Derive {
        keyword: Ident,
        mutability: Option<Token![mut]>,
        scope: Ident,
        body: Group,
    },
}

/// `name: Type ~ dist(args)`.
pub struct Param {
    pub attrs: Vec<Attribute>,
    pub name: Ident,
    pub ty: Type,
    pub dist: Ident,
    pub paren: token::Paren,
    pub args: Punctuated<Expr, Token![,]>,
}

/// `name: Node = p` or `name: [Node; N] = p`.
pub struct Slot {
    pub attrs: Vec<Attribute>,
    pub name: Ident,
    pub target: SlotTarget,
    pub probability: Expr,
}

/// The node type of a slot.
pub enum SlotTarget {
    /// `Node`: one optional child.
    Single(Ident),
    /// `[Node; N]`: `N` optional children.
    Array { node: Ident, len: Expr },
}

impl SlotTarget {
    /// The child's node name.
    pub fn node(&self) -> &Ident {
        match self {
            SlotTarget::Single(n) | SlotTarget::Array { node: n, .. } => n,
        }
    }
}

/// Parses the macro's input, recording recoverable mistakes in `cx`. An `Err` means not
/// even the generator's name could be read.
pub fn parse_input(tokens: TokenStream, cx: &Ctxt) -> Result<Input> {
    let parser = |input: ParseStream| {
        let mut krate = TokenStream::new();
        while !input.peek(Token![;]) {
            if input.is_empty() {
                return Err(input.error(
                    "expected the runtime's path and `;`; use `shapegen::generator!`, \
                     not `generator_impl!`",
                ));
            }
            krate.extend([input.parse::<TokenTree>()?]);
        }
        input.parse::<Token![;]>()?;
        let generator = parse_generator(input, cx)?;
        Ok(Input { krate, generator })
    };
    parser.parse2(tokens)
}

fn parse_generator(input: ParseStream, cx: &Ctxt) -> Result<Generator> {
    let attrs = input.call(Attribute::parse_outer)?;
    let vis: Visibility = input.parse()?;
    if input.peek(kw::node) || input.peek(kw::axiom) {
        return Err(input.error(
            "expected the generator's name first: `generator! { pub Name { axiom Start; node \
             Start { .. } } }`",
        ));
    }
    let name: Ident = input.parse().map_err(|e| {
        Error::new(
            e.span(),
            "expected the generator's name: `generator! { pub Name { axiom Start; node Start \
             { .. } } }`",
        )
    })?;
    if !input.peek(token::Brace) {
        return Err(input.error(format!(
            "expected `{{` after the generator's name: `{name} {{ axiom Start; node Start {{ .. \
             }} }}`"
        )));
    }
    let content;
    braced!(content in input);
    let mut items = Vec::new();
    while !content.is_empty() {
        match attempt(&content, |s| parse_item(s, cx)) {
            Ok(item) => items.push(item),
            Err(e) => {
                cx.push(e);
                skip_until(&content, |s| {
                    s.peek(kw::node) || s.peek(kw::axiom) || s.peek(kw::meshes) || s.peek(Token![#])
                });
            }
        }
    }
    if !input.is_empty() {
        cx.push(input.error(format!(
            "unexpected tokens after the body of generator `{name}`; declare one generator per \
             `generator!`"
        )));
        let _ = input.parse::<TokenStream>();
    }
    Ok(Generator {
        attrs,
        vis,
        name,
        items,
    })
}

/// Runs `f` on a fork of `input` and advances `input` only if it succeeds, so that a
/// failed attempt leaves no half-parsed group behind (syn would report it as an extra
/// "unexpected token" at the end) and `input` can skip from the attempt's start.
fn attempt<T>(input: ParseStream, f: impl FnOnce(ParseStream) -> Result<T>) -> Result<T> {
    let fork = input.fork();
    let out = f(&fork)?;
    input.advance_to(&fork);
    Ok(out)
}

/// Skips token trees until `stop` holds or the stream ends; always skips at least one.
fn skip_until(input: ParseStream, stop: impl Fn(ParseStream) -> bool) {
    let _ = input.parse::<TokenTree>();
    while !input.is_empty() && !stop(input) {
        let _ = input.parse::<TokenTree>();
    }
}

fn parse_item(input: ParseStream, cx: &Ctxt) -> Result<Item> {
    let attrs = input.call(Attribute::parse_outer)?;
    let lookahead = input.lookahead1();
    if lookahead.peek(kw::node) {
        input.parse::<kw::node>()?;
        let name: Ident = input
            .parse()
            .map_err(|e| Error::new(e.span(), "expected the node's name: `node Name { .. }`"))?;
        if !input.peek(token::Brace) {
            return Err(input.error(format!(
                "expected `{{` after `node {name}`: a node's body holds its sections, \
                 `params {{ .. }}`, `children {{ .. }}` and `derive(s) {{ .. }}`"
            )));
        }
        let content;
        braced!(content in input);
        let (sections, broken) = parse_sections(&content, cx);
        return Ok(Item::Node(Node {
            attrs,
            name,
            sections,
            broken,
        }));
    }
    let not_here = |what: &str| {
        Error::new_spanned(
            quote::quote!(#(#attrs)*),
            format!(
                "attributes are not allowed on {what}; put them on nodes, parameters or meshes"
            ),
        )
    };
    if lookahead.peek(kw::axiom) {
        if !attrs.is_empty() {
            return Err(not_here("`axiom`"));
        }
        let keyword = input.call(Ident::parse_any)?;
        let node: Ident = input.parse().map_err(|e| {
            Error::new(
                e.span(),
                "expected the name of the axiom node: `axiom Start;`",
            )
        })?;
        input
            .parse::<Token![;]>()
            .map_err(|e| Error::new(e.span(), format!("expected `;` after `axiom {node}`")))?;
        return Ok(Item::Axiom { keyword, node });
    }
    if lookahead.peek(kw::meshes) {
        if !attrs.is_empty() {
            return Err(not_here("the `meshes` block; put them on its entries"));
        }
        let keyword = input.call(Ident::parse_any)?;
        if !input.peek(token::Brace) {
            return Err(input.error(
                "expected `{` after `meshes`: `meshes { TRUNK = \"trunk\", LEAF = \"leaf\" }`",
            ));
        }
        let content;
        braced!(content in input);
        let (meshes, _) = parse_list(&content, cx, Mesh::parse);
        return Ok(Item::Meshes { keyword, meshes });
    }
    let mut e = lookahead.error();
    if input.peek(syn::Ident) {
        let ident: Ident = input.fork().parse()?;
        e = Error::new(
            ident.span(),
            format!(
                "expected `axiom`, `meshes` or `node`, found `{ident}`; a generator's body \
                 holds `axiom Start;`, an optional `meshes {{ .. }}` block and `node Name {{ .. \
                 }}` declarations"
            ),
        );
    }
    Err(e)
}

/// Parses a comma-separated list, recovering at the next top-level comma after a
/// mistake. Returns the entries that parsed and whether all did.
fn parse_list<T>(input: ParseStream, cx: &Ctxt, f: fn(ParseStream) -> Result<T>) -> (Vec<T>, bool) {
    let mut out = Vec::new();
    let mut ok = true;
    while !input.is_empty() {
        match attempt(input, f) {
            Ok(t) => {
                out.push(t);
                if input.is_empty() {
                    break;
                }
                if let Err(e) = input.parse::<Token![,]>() {
                    cx.push(Error::new(
                        e.span(),
                        "expected `,` between entries (or the end of the list)",
                    ));
                    ok = false;
                    skip_past_comma(input);
                }
            }
            Err(e) => {
                cx.push(e);
                ok = false;
                skip_past_comma(input);
            }
        }
    }
    (out, ok)
}

fn skip_past_comma(input: ParseStream) {
    while !input.is_empty() {
        if input.parse::<Token![,]>().is_ok() {
            return;
        }
        let _ = input.parse::<TokenTree>();
    }
}

/// Parses a node's sections; returns them and whether some part failed to parse.
fn parse_sections(input: ParseStream, cx: &Ctxt) -> (Vec<Section>, bool) {
    let mut sections = Vec::new();
    let mut broken = false;
    let is_section =
        |s: ParseStream| s.peek(kw::params) || s.peek(kw::children) || s.peek(kw::derive);
    while !input.is_empty() {
        match attempt(input, |s| parse_section(s, cx)) {
            Ok((section, ok)) => {
                sections.extend(section);
                broken |= !ok;
            }
            Err(e) => {
                cx.push(e);
                broken = true;
                skip_until(input, is_section);
            }
        }
    }
    (sections, broken)
}

const SECTIONS: &str = "a node holds `params { .. }`, `children { .. }` and `derive(s) { .. }`, \
                        each at most once";

/// Parses one section. `Ok((None, false))` is an unknown section, already reported and
/// skipped.
fn parse_section(input: ParseStream, cx: &Ctxt) -> Result<(Option<Section>, bool)> {
    if input.peek(Token![#]) {
        let attrs = input.call(Attribute::parse_outer)?;
        return Err(Error::new_spanned(
            quote::quote!(#(#attrs)*),
            "attributes are not allowed on sections; put them before `node`, or on parameters",
        ));
    }
    if !input.peek(Ident::peek_any) {
        let tt: TokenTree = input.parse()?;
        return Err(Error::new_spanned(
            tt,
            format!("expected a section; {SECTIONS}"),
        ));
    }
    let keyword: Ident = input.call(Ident::parse_any)?;
    match keyword.to_string().as_str() {
        "params" => {
            let content = section_body(
                input,
                &keyword,
                "params { size: Vec3 ~ uniform([0.5; 3], [1.5; 3]) }",
            )?;
            let (params, ok) = parse_list(&content, cx, Param::parse);
            Ok((Some(Section::Params { keyword, params }), ok))
        }
        "children" => {
            let content = section_body(input, &keyword, "children { next: Body = 0.5 }")?;
            let (slots, ok) = parse_list(&content, cx, Slot::parse);
            Ok((Some(Section::Children { keyword, slots }), ok))
        }
        "derive" => parse_derive(input, keyword).map(|section| (Some(section), true)),
        other => {
            let hint = match other {
                "param" | "parameters" | "params_" => " (did you mean `params`?)",
                "child" | "children_" | "slots" => " (did you mean `children`?)",
                "rule" | "derivation" | "body" => " (did you mean `derive`?)",
                _ => "",
            };
            cx.push(Error::new(
                keyword.span(),
                format!("unknown section `{other}`{hint}; {SECTIONS}"),
            ));
            if input.peek(token::Paren) {
                let _ = input.parse::<TokenTree>();
            }
            if input.peek(token::Brace) {
                let _ = input.parse::<TokenTree>();
            }
            Ok((None, false))
        }
    }
}

/// The rest of a `derive` section after its `keyword`: the scope's name in parentheses
/// (with `mut` if written), then the rule's body in braces.
fn parse_derive(input: ParseStream, keyword: Ident) -> Result<Section> {
    if !input.peek(token::Paren) {
        return Err(Error::new(
            keyword.span(),
            "`derive` names the scope it works in: `derive(s) { s.emit(CUBE); }`",
        ));
    }
    let args;
    parenthesized!(args in input);
    let mutability: Option<Token![mut]> = args.parse()?;
    let scope: Ident = args.parse().map_err(|e| {
        Error::new(
            e.span(),
            "expected the name of the scope: `derive(s) { .. }` or `derive(mut s) { .. }`",
        )
    })?;
    if !args.is_empty() {
        return Err(args.error(
            "`derive` takes only the scope's name: `derive(s) { .. }`; parameters and \
             children are bound by their own names",
        ));
    }
    match input.parse::<TokenTree>() {
        Ok(TokenTree::Group(body)) if body.delimiter() == Delimiter::Brace => Ok(Section::Derive {
            keyword,
            mutability,
            scope,
            body,
        }),
        Ok(tt) => Err(Error::new_spanned(
            tt,
            format!("expected the rule's body in braces: `derive({scope}) {{ .. }}`"),
        )),
        Err(e) => Err(Error::new(
            e.span(),
            format!("expected the rule's body in braces: `derive({scope}) {{ .. }}`"),
        )),
    }
}

/// The braced body of a `params` or `children` section.
fn section_body<'a>(
    input: ParseStream<'a>,
    keyword: &Ident,
    example: &str,
) -> Result<syn::parse::ParseBuffer<'a>> {
    if !input.peek(token::Brace) {
        return Err(Error::new(
            keyword.span(),
            format!("expected `{{` after `{keyword}`: `{example}`"),
        ));
    }
    let content;
    braced!(content in input);
    Ok(content)
}

impl Parse for Mesh {
    fn parse(input: ParseStream) -> Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let name: Ident = input.parse()?;
        input.parse::<Token![=]>().map_err(|e| {
            Error::new(
                e.span(),
                format!(
                    "expected `=` and the mesh's name: `{name} = \"{}\"`",
                    name.to_string().to_lowercase()
                ),
            )
        })?;
        let file: LitStr = input.parse().map_err(|e| {
            Error::new(
                e.span(),
                format!(
                    "expected the mesh's name as a string: `{name} = \"{}\"`",
                    name.to_string().to_lowercase()
                ),
            )
        })?;
        Ok(Mesh { attrs, name, file })
    }
}

impl Parse for Param {
    fn parse(input: ParseStream) -> Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let name: Ident = input.parse()?;
        input.parse::<Token![:]>().map_err(|e| {
            Error::new(
                e.span(),
                format!("expected `:` and the parameter's type: `{name}: f32 ~ uniform(0.0, 1.0)`"),
            )
        })?;
        let ty: Type = input.parse()?;
        input.parse::<Token![~]>().map_err(|e| {
            Error::new(
                e.span(),
                format!(
                    "expected `~` and the parameter's distribution: `{name}: f32 ~ uniform(0.0, \
                     1.0)`"
                ),
            )
        })?;
        let dist: Ident = input.parse().map_err(|e| {
            Error::new(
                e.span(),
                "expected a distribution such as `uniform(lo, hi)` after `~`",
            )
        })?;
        if !input.peek(token::Paren) {
            return Err(input.error(format!(
                "expected the arguments of `{dist}` in parentheses, as in `{dist}(..)`"
            )));
        }
        let content;
        let paren = parenthesized!(content in input);
        let args = content.parse_terminated(Expr::parse, Token![,])?;
        Ok(Param {
            attrs,
            name,
            ty,
            dist,
            paren,
            args,
        })
    }
}

impl Parse for Slot {
    fn parse(input: ParseStream) -> Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let name: Ident = input.parse()?;
        input.parse::<Token![:]>().map_err(|e| {
            Error::new(
                e.span(),
                format!("expected `:` and the child's node: `{name}: Node = 0.5`"),
            )
        })?;
        let target = if input.peek(token::Bracket) {
            let content;
            bracketed!(content in input);
            let node: Ident = content.parse()?;
            content.parse::<Token![;]>().map_err(|e| {
                Error::new(
                    e.span(),
                    format!("expected `;` and the number of slots: `[{node}; 4]`"),
                )
            })?;
            let len: Expr = content.parse()?;
            if !content.is_empty() {
                return Err(content.error(format!("expected `]`: an array slot is `[{node}; N]`")));
            }
            SlotTarget::Array { node, len }
        } else {
            SlotTarget::Single(input.parse().map_err(|e| {
                Error::new(
                    e.span(),
                    format!("expected the child's node: `{name}: Node = 0.5` or `{name}: [Node; 4] = 0.5`"),
                )
            })?)
        };
        input.parse::<Token![=]>().map_err(|e| {
            Error::new(
                e.span(),
                format!(
                    "expected `=` and the probability that the child appears: `{name}: {} = 0.5`",
                    target.node()
                ),
            )
        })?;
        let probability: Expr = input.parse()?;
        Ok(Slot {
            attrs,
            name,
            target,
            probability,
        })
    }
}
