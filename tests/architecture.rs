//! The modules of the facade crate (and of the runtime, generators and macro crates) import one
//! another without loops, and no module imports from a module above it (its parent's hub, or further up): the types that children
//! share live in a module of their own, and a parent's `mod.rs` declares its children and
//! re-exports what it offers outside (`docs/architecture.md`, "Modules").
//!
//! The check reads the source files of `src/` (all of them, whatever the features; not
//! `main.rs`, the binary), builds the graph of which module imports which, and fails
//! listing every loop and every upward import. An import is any path that names an item
//! of the crate: in a `use`, in code, in an attribute's arguments (`help = crate::...`)
//! or in a macro's tokens (`crate::...`, `super::...`). A path is followed through the
//! `use` items (re-exports) of the modules it passes to the module that defines the
//! item, so that `crate::scene::Scene` is an import of the module that defines `Scene`,
//! not of `scene`; an item no module defines by name (one a macro makes) belongs to the
//! module the path names. A path that starts with the name the crate gives itself
//! (`extern crate self as shapegen`, read from its root) starts at its root, as `crate::`
//! does; a macro exported at the root (`#[macro_export]`) is the module's that defines it,
//! so that `crate::checkpoint!` imports that module, not the root. An inline module (`mod tests { ... }`) counts as part of its
//! file's module, and so does a module of tests in a file of its own (`check/tests.rs`,
//! declared `#[cfg(test)] mod tests;`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use proc_macro2::{TokenStream, TokenTree};
use syn::visit::Visit;

/// A module, as the names from the crate root down (`["scene", "error"]`).
type ModPath = Vec<String>;

/// The name a crate gives itself (`extern crate self as shapegen`, as the facade does so
/// that its tool names it as its users do), read from its root's items: paths that start
/// with it start at the crate's root, as `crate::` paths do.
fn self_alias(items: &[syn::Item]) -> Option<String> {
    items.iter().find_map(|item| match item {
        syn::Item::ExternCrate(e) if e.ident == "self" => {
            e.rename.as_ref().map(|(_, alias)| alias.to_string())
        }
        _ => None,
    })
}

/// What the items of one module (a file's, or an inline one's) say about names.
#[derive(Default)]
struct Scope {
    /// The file's module that the module is part of.
    file: ModPath,
    /// The names it defines (structs, enums, functions, ...).
    defined: BTreeSet<String>,
    /// The names its `use` items bring in, with the path each names.
    uses: BTreeMap<String, Vec<String>>,
    /// The paths of its glob imports (`use x::*`).
    globs: Vec<Vec<String>>,
}

/// Where a path leads: the last module it names, and the module that defines its item.
struct Resolved {
    /// The module whose namespace the path takes its item from.
    via: ModPath,
    /// The module that defines the item (the module itself when the path names one).
    target: ModPath,
}

/// The crate's modules and what they import.
struct Crate {
    /// The name the crate gives itself (`extern crate self as ...`), if any.
    alias: Option<String>,
    /// Every module, file and inline, by its path.
    scopes: BTreeMap<ModPath, Scope>,
    /// The macros exported at the crate's root (`#[macro_export]`), each with the module
    /// that defines it.
    exported: BTreeMap<String, ModPath>,
    /// For each file's module, the file's modules it imports, each with the first path
    /// that does and where it is written.
    edges: BTreeMap<ModPath, BTreeMap<ModPath, String>>,
    /// Imports of an item through a module above the importer, in words.
    upward: BTreeSet<String>,
}

/// The module a source file holds, from its path relative to `src/` (`scene/mod.rs` is
/// `scene`, `lib.rs` the root); `None` for the binary's `main.rs`.
fn module_of(file: &str) -> Option<ModPath> {
    let stem = file.strip_suffix(".rs")?;
    let mut path: ModPath = stem.split('/').map(str::to_owned).collect();
    match path.last().map(String::as_str) {
        Some("main") if path.len() == 1 => return None,
        Some("lib") if path.len() == 1 => path.clear(),
        Some("mod") => {
            path.pop();
        }
        _ => {}
    }
    Some(path)
}

/// The module in words: `scene::error`, or `crate` for the root.
fn name(path: &[String]) -> String {
    if path.is_empty() {
        "crate".to_owned()
    } else {
        path.join("::")
    }
}

/// Adds the names and paths of a `use` tree under `prefix` to `scope`.
fn add_use(scope: &mut Scope, prefix: &mut Vec<String>, tree: &syn::UseTree) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            add_use(scope, prefix, &p.tree);
            prefix.pop();
        }
        syn::UseTree::Name(n) => {
            let (alias, path) = use_name(prefix, &n.ident, &n.ident);
            scope.uses.insert(alias, path);
        }
        syn::UseTree::Rename(r) => {
            let (alias, path) = use_name(prefix, &r.ident, &r.rename);
            scope.uses.insert(alias, path);
        }
        syn::UseTree::Glob(_) => scope.globs.push(prefix.clone()),
        syn::UseTree::Group(g) => {
            for tree in &g.items {
                add_use(scope, prefix, tree);
            }
        }
    }
}

/// The name a `use` of `ident` under `prefix` brings in (`alias`), and the path it names;
/// `x::{self}` names the module `x`.
fn use_name(prefix: &[String], ident: &syn::Ident, alias: &syn::Ident) -> (String, Vec<String>) {
    let mut path = prefix.to_vec();
    let alias = if ident == "self" {
        prefix.last().cloned().unwrap_or_default()
    } else {
        path.push(ident.to_string());
        alias.to_string()
    };
    (alias, path)
}

/// Every path of a `use` tree, each from the root of the tree.
fn use_paths(tree: &syn::UseTree, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            use_paths(&p.tree, prefix, out);
            prefix.pop();
        }
        syn::UseTree::Name(syn::UseName { ident, .. })
        | syn::UseTree::Rename(syn::UseRename { ident, .. }) => {
            let mut path = prefix.clone();
            if ident != "self" {
                path.push(ident.to_string());
            }
            out.push(path);
        }
        syn::UseTree::Glob(_) => out.push(prefix.clone()),
        syn::UseTree::Group(g) => {
            for tree in &g.items {
                use_paths(tree, prefix, out);
            }
        }
    }
}

/// The name an item defines, for the items that define one a path can name.
fn defined_name(item: &syn::Item) -> Option<String> {
    let ident = match item {
        syn::Item::Const(i) => &i.ident,
        syn::Item::Enum(i) => &i.ident,
        syn::Item::Fn(i) => &i.sig.ident,
        syn::Item::Static(i) => &i.ident,
        syn::Item::Struct(i) => &i.ident,
        syn::Item::Trait(i) => &i.ident,
        syn::Item::Type(i) => &i.ident,
        syn::Item::Union(i) => &i.ident,
        syn::Item::Macro(i) => i.ident.as_ref()?,
        _ => return None,
    };
    Some(ident.to_string())
}

/// The paths written in a macro's or an attribute's tokens that start at a module:
/// `crate::a::B`, `super::B`, `self::a::B` (and the crate's own name).
fn token_paths(tokens: TokenStream, alias: Option<&str>, out: &mut Vec<Vec<String>>) {
    let tokens: Vec<TokenTree> = tokens.into_iter().collect();
    let mut i = 0;
    while i < tokens.len() {
        match &tokens[i] {
            TokenTree::Group(group) => token_paths(group.stream(), alias, out),
            TokenTree::Ident(ident) => {
                let first = ident.to_string();
                let starts = ["crate", "super", "self"].contains(&first.as_str())
                    || alias == Some(first.as_str());
                let after_colons =
                    i >= 1 && matches!(&tokens[i - 1], TokenTree::Punct(p) if p.as_char() == ':');
                if starts && !after_colons {
                    let mut path = vec![first];
                    while let (
                        Some(TokenTree::Punct(a)),
                        Some(TokenTree::Punct(b)),
                        Some(TokenTree::Ident(next)),
                    ) = (tokens.get(i + 1), tokens.get(i + 2), tokens.get(i + 3))
                    {
                        if a.as_char() != ':' || b.as_char() != ':' {
                            break;
                        }
                        path.push(next.to_string());
                        i += 3;
                    }
                    if path.len() > 1 {
                        out.push(path);
                    }
                }
            }
            _ => {}
        }
        i += 1;
    }
}

/// Gathers the paths written in a module's items but its `use` items and inline modules,
/// which are read apart.
struct Paths<'a> {
    /// The name the crate gives itself, if any.
    alias: Option<&'a str>,
    /// The paths, as the names they are made of.
    found: Vec<Vec<String>>,
}

impl<'ast> Visit<'ast> for Paths<'_> {
    fn visit_path(&mut self, path: &'ast syn::Path) {
        // A path of one name is a local name, or an imported one whose `use` counts.
        if path.leading_colon.is_none() && path.segments.len() > 1 {
            self.found
                .push(path.segments.iter().map(|s| s.ident.to_string()).collect());
        }
        syn::visit::visit_path(self, path);
    }

    fn visit_item_use(&mut self, item: &'ast syn::ItemUse) {
        // A `use` inside a function: an import as any other.
        use_paths(&item.tree, &mut Vec::new(), &mut self.found);
    }

    fn visit_item_mod(&mut self, _: &'ast syn::ItemMod) {
        // An inline module is a module of its own, read on its own.
    }

    fn visit_vis_restricted(&mut self, _: &'ast syn::VisRestricted) {
        // `pub(in crate::x)` says who may use an item; it imports nothing.
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        syn::visit::visit_macro(self, mac);
        token_paths(mac.tokens.clone(), self.alias, &mut self.found);
    }

    fn visit_meta_list(&mut self, list: &'ast syn::MetaList) {
        syn::visit::visit_meta_list(self, list);
        token_paths(list.tokens.clone(), self.alias, &mut self.found);
    }
}

impl Crate {
    /// Reads `files` (each a path relative to `src/` with its text) and builds the graph.
    fn read(files: &[(String, String)]) -> Crate {
        let mut parsed = Vec::new();
        for (file, text) in files {
            let Some(module) = module_of(file) else {
                continue;
            };
            let ast = syn::parse_file(text).unwrap_or_else(|err| panic!("{file}: {err}"));
            // A file of tests counts as part of the module that declares it.
            let mut owner = module.clone();
            if owner.last().is_some_and(|last| last == "tests") {
                owner.pop();
            }
            parsed.push((file.clone(), owner, module, ast));
        }
        let alias = parsed
            .iter()
            .find(|(_, _, module, _)| module.is_empty())
            .and_then(|(_, _, _, ast)| self_alias(&ast.items));
        let mut krate = Crate {
            alias,
            scopes: BTreeMap::new(),
            exported: BTreeMap::new(),
            edges: BTreeMap::new(),
            upward: BTreeSet::new(),
        };
        for (_, owner, module, ast) in &parsed {
            krate.add_scope(owner, module, &ast.items);
        }
        for (file, owner, module, ast) in &parsed {
            krate.edges.entry(owner.clone()).or_default();
            krate.add_imports(file, owner, module, &ast.items);
        }
        krate
    }

    /// Records the module at `path`, part of the file's module `file`, and its inline
    /// modules.
    fn add_scope(&mut self, file: &ModPath, path: &ModPath, items: &[syn::Item]) {
        let mut scope = Scope {
            file: file.clone(),
            ..Scope::default()
        };
        for item in items {
            match item {
                syn::Item::Use(u) if u.leading_colon.is_none() => {
                    add_use(&mut scope, &mut Vec::new(), &u.tree);
                }
                syn::Item::Mod(m) => {
                    if let Some((_, content)) = &m.content {
                        let mut inner = path.clone();
                        inner.push(m.ident.to_string());
                        self.add_scope(file, &inner, content);
                    }
                }
                _ => {
                    if let Some(name) = defined_name(item) {
                        if let syn::Item::Macro(m) = item
                            && m.attrs.iter().any(|a| a.path().is_ident("macro_export"))
                        {
                            self.exported.insert(name.clone(), path.clone());
                        }
                        scope.defined.insert(name);
                    }
                }
            }
        }
        self.scopes.insert(path.clone(), scope);
    }

    /// Records what the module at `path` (part of the file's module `module`, written
    /// in `file`) imports, and its inline modules'.
    fn add_imports(&mut self, file: &str, module: &ModPath, path: &ModPath, items: &[syn::Item]) {
        let alias = self.alias.clone();
        let mut paths = Paths {
            alias: alias.as_deref(),
            found: Vec::new(),
        };
        for item in items {
            match item {
                syn::Item::Use(u) if u.leading_colon.is_none() => {
                    use_paths(&u.tree, &mut Vec::new(), &mut paths.found);
                }
                syn::Item::Mod(m) => {
                    for attr in &m.attrs {
                        paths.visit_attribute(attr);
                    }
                    if let Some((_, content)) = &m.content {
                        let mut inner = path.clone();
                        inner.push(m.ident.to_string());
                        self.add_imports(file, module, &inner, content);
                    }
                }
                _ => paths.visit_item(item),
            }
        }
        for written in paths.found {
            let Some(resolved) = self.resolve(path, &written, 0) else {
                continue;
            };
            let target = self.file_of(&resolved.target);
            if target == *module {
                continue;
            }
            let text = written.join("::");
            // A path that starts at a name a `use` brought in is that `use`'s import,
            // told once, at the `use`.
            let mut child = path.clone();
            child.push(written[0].clone());
            let direct = ["super", "self"].contains(&written[0].as_str())
                || self.is_root(&written[0])
                || self.is_module(&child);
            let above = resolved.via.len() < module.len() && module.starts_with(&resolved.via);
            if direct && above {
                self.upward.insert(format!(
                    "{} imports `{text}` ({file}) through `{}`, a module above it",
                    name(module),
                    name(&resolved.via),
                ));
            }
            self.edges
                .entry(module.clone())
                .or_default()
                .entry(target)
                .or_insert_with(|| format!("`{text}` ({file})"));
        }
    }

    /// The file's module that the module at `path` is part of.
    fn file_of(&self, path: &ModPath) -> ModPath {
        self.scopes
            .get(path)
            .map_or_else(|| path.clone(), |scope| scope.file.clone())
    }

    /// Whether a path that starts with `first` starts at the crate's root: `crate`, or
    /// the name the crate gives itself.
    fn is_root(&self, first: &str) -> bool {
        first == "crate" || self.alias.as_deref() == Some(first)
    }

    /// Whether `path` is a module of the crate.
    fn is_module(&self, path: &[String]) -> bool {
        self.scopes.contains_key(path)
    }

    /// Where `path`, written in the module `scope`, leads; `None` for a path outside the
    /// crate (another crate's, a local name's).
    fn resolve(&self, scope: &ModPath, path: &[String], depth: usize) -> Option<Resolved> {
        let first = path.first()?.as_str();
        if depth > 32 {
            return None;
        }
        let mut module;
        let mut rest = path;
        match first {
            _ if self.is_root(first) => {
                module = Vec::new();
                rest = &path[1..];
            }
            "self" => {
                module = scope.clone();
                rest = &path[1..];
            }
            "super" => {
                module = scope.clone();
                while rest.first().is_some_and(|s| s == "super") {
                    module.pop()?;
                    rest = &rest[1..];
                }
            }
            _ => {
                module = scope.clone();
                let mut child = scope.clone();
                child.push(first.to_owned());
                if !self.is_module(&child) {
                    let imported = self.scopes.get(scope)?.uses.get(first)?;
                    let mut full = imported.clone();
                    full.extend_from_slice(&path[1..]);
                    return self.resolve(scope, &full, depth + 1);
                }
            }
        }
        // An exported macro is named at the root but is its defining module's.
        if module.is_empty()
            && let Some(defining) = rest.first().and_then(|m| self.exported.get(m))
        {
            module = defining.clone();
        }
        while let Some(segment) = rest.first() {
            let mut child = module.clone();
            child.push(segment.clone());
            if !self.is_module(&child) {
                break;
            }
            module = child;
            rest = &rest[1..];
        }
        let target = match rest.first() {
            None => module.clone(),
            Some(item) => self.defining(&module, item, depth)?,
        };
        Some(Resolved {
            via: module,
            target,
        })
    }

    /// The module that defines the item `item` of the module `module`, following its
    /// `use` items; `None` when the item comes from outside the crate.
    fn defining(&self, module: &ModPath, item: &str, depth: usize) -> Option<ModPath> {
        let scope = self.scopes.get(module)?;
        if scope.defined.contains(item) {
            return Some(module.clone());
        }
        if let Some(path) = scope.uses.get(item) {
            return self.resolve(module, path, depth + 1).map(|r| r.target);
        }
        let mut outside = false;
        for glob in &scope.globs {
            match self.resolve(module, glob, depth + 1) {
                Some(r) => {
                    let from = self.scopes.get(&r.target)?;
                    if from.defined.contains(item) || from.uses.contains_key(item) {
                        return self.defining(&r.target, item, depth + 1);
                    }
                }
                None => outside = true,
            }
        }
        // No module defines it by name: a macro made it here, or (behind a glob import
        // of another crate) it is that crate's.
        (!outside).then(|| module.clone())
    }

    /// Every loop of imports, each as its modules and the imports between them.
    fn cycles(&self) -> Vec<String> {
        let nodes: Vec<&ModPath> = self.edges.keys().collect();
        let index: BTreeMap<&ModPath, usize> =
            nodes.iter().enumerate().map(|(i, n)| (*n, i)).collect();
        let next: Vec<Vec<usize>> = nodes
            .iter()
            .map(|n| {
                self.edges[*n]
                    .keys()
                    .filter_map(|t| index.get(t).copied())
                    .collect()
            })
            .collect();
        strongly_connected(&next)
            .into_iter()
            .filter(|component| component.len() > 1)
            .map(|component| {
                let members: BTreeSet<&ModPath> = component.iter().map(|&i| nodes[i]).collect();
                let mut text = format!(
                    "import loop among {}:",
                    members
                        .iter()
                        .map(|m| name(m))
                        .collect::<Vec<_>>()
                        .join(", ")
                );
                for from in &members {
                    for (to, example) in &self.edges[*from] {
                        if members.contains(to) {
                            text.push_str(&format!(
                                "\n    {} -> {}: {example}",
                                name(from),
                                name(to)
                            ));
                        }
                    }
                }
                text
            })
            .collect()
    }

    /// What is wrong: the loops, then the upward imports.
    fn problems(&self) -> Vec<String> {
        let mut problems = self.cycles();
        problems.extend(self.upward.iter().cloned());
        problems
    }
}

/// The strongly connected components of the graph whose node `i` leads to `next[i]`
/// (Tarjan's algorithm, iteratively).
fn strongly_connected(next: &[Vec<usize>]) -> Vec<Vec<usize>> {
    let n = next.len();
    let mut index = vec![usize::MAX; n];
    let mut low = vec![0; n];
    let mut on_stack = vec![false; n];
    let mut stack = Vec::new();
    let mut components = Vec::new();
    let mut counter = 0;
    for root in 0..n {
        if index[root] != usize::MAX {
            continue;
        }
        let mut work = vec![(root, 0)];
        while let Some(&mut (v, ref mut edge)) = work.last_mut() {
            if *edge == 0 && index[v] == usize::MAX {
                index[v] = counter;
                low[v] = counter;
                counter += 1;
                stack.push(v);
                on_stack[v] = true;
            }
            if let Some(&w) = next[v].get(*edge) {
                *edge += 1;
                if index[w] == usize::MAX {
                    work.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            work.pop();
            if let Some(&(parent, _)) = work.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut component = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                components.push(component);
            }
        }
    }
    components
}

/// The source files under `dir`, each with its path relative to `root`.
fn read_dir(root: &Path, dir: &Path, out: &mut Vec<(String, String)>) {
    for entry in std::fs::read_dir(dir).expect("the folder reads") {
        let path = entry.expect("the folder reads").path();
        if path.is_dir() {
            read_dir(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path.strip_prefix(root).expect("under the root");
            let relative = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/");
            let text = std::fs::read_to_string(&path).expect("the file reads");
            out.push((relative, text));
        }
    }
}

/// The problems of the crate made of `files` (path relative to `src/`, text).
fn problems_of(files: &[(&str, &str)]) -> Vec<String> {
    let files: Vec<(String, String)> = files
        .iter()
        .map(|(p, t)| (p.to_string(), t.to_string()))
        .collect();
    Crate::read(&files).problems()
}

#[test]
fn the_facade_crate_has_no_import_loop_and_no_upward_import() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    read_dir(&src, &src, &mut files);
    let krate = Crate::read(&files);
    assert!(krate.edges.len() > 40, "{} modules read", krate.edges.len());
    let problems = krate.problems();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_runtime_generators_and_macro_crates_have_no_import_loop_and_no_upward_import() {
    for dir in [
        "shapegen-runtime/src",
        "generators/src",
        "shapegen-macros/src",
    ] {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        let mut files = Vec::new();
        read_dir(&src, &src, &mut files);
        let krate = Crate::read(&files);
        assert!(
            krate.edges.len() > 5,
            "{dir}: {} modules read",
            krate.edges.len()
        );
        let problems = krate.problems();
        assert!(problems.is_empty(), "{dir}:\n{}", problems.join("\n"));
    }
}

#[test]
fn a_loop_of_imports_is_found_directly_and_around_modules() {
    let direct = problems_of(&[
        ("lib.rs", "mod a; mod b;"),
        ("a.rs", "use crate::b::B; pub struct A(B);"),
        ("b.rs", "pub struct B; fn f() -> crate::a::A { todo!() }"),
    ]);
    assert_eq!(direct.len(), 1, "{direct:?}");
    assert!(
        direct[0].starts_with("import loop among a, b:"),
        "{direct:?}"
    );
    let around = problems_of(&[
        ("lib.rs", "mod a; mod b; mod c;"),
        ("a.rs", "use crate::b::B; pub struct A;"),
        ("b.rs", "use super::c::C; pub struct B;"),
        ("c.rs", "pub struct C; m! { crate::a::A }"),
    ]);
    assert_eq!(around.len(), 1, "{around:?}");
    assert!(
        around[0].starts_with("import loop among a, b, c:"),
        "{around:?}"
    );
}

#[test]
fn a_path_through_a_re_export_imports_the_module_that_defines_the_item() {
    // `y` imports `X` through its parent's re-export: an upward import, but no loop,
    // since `x` defines `X` and imports nothing.
    let files = [
        ("lib.rs", "mod hub;"),
        ("hub/mod.rs", "mod x; mod y; pub use x::X; pub use y::Y;"),
        ("hub/x.rs", "pub struct X;"),
        ("hub/y.rs", "use super::X; pub struct Y(X);"),
    ];
    let problems = problems_of(&files);
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(
        problems[0].starts_with("hub::y imports `super::X`"),
        "{problems:?}"
    );
    // Through the sibling module instead, nothing is wrong.
    let files = [
        files[0],
        files[1],
        files[2],
        ("hub/y.rs", "use super::x::X; pub struct Y(X);"),
    ];
    assert_eq!(problems_of(&files), Vec::<String>::new());
}

#[test]
fn a_child_that_imports_what_its_hub_defines_is_found_with_the_loop() {
    let problems = problems_of(&[
        ("lib.rs", "pub mod hub;"),
        ("hub/mod.rs", "mod c; pub use c::C; pub struct H;"),
        ("hub/c.rs", "pub struct C(crate::hub::H);"),
    ]);
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(
        problems[0].starts_with("import loop among hub, hub::c:"),
        "{problems:?}"
    );
    assert!(
        problems[1].starts_with("hub::c imports `crate::hub::H`"),
        "{problems:?}"
    );
}

#[test]
fn tests_modules_visibility_and_other_crates_import_nothing() {
    let problems = problems_of(&[
        ("lib.rs", "pub use other::*; mod a; mod b;"),
        (
            "a.rs",
            "pub(in crate::a) struct A; #[cfg(test)] mod tests { use super::*; }",
        ),
        (
            "b.rs",
            "use crate::Other; use crate::a::A; fn f() -> shapegen::Thing { todo!() } \
             #[cfg(test)] mod tests;",
        ),
        ("b/tests.rs", "use super::*; use crate::a::A;"),
    ]);
    assert_eq!(problems, Vec::<String>::new());
    // A file of tests is part of the module that declares it: its imports are that
    // module's.
    let looped = problems_of(&[
        ("lib.rs", "mod a; mod b;"),
        ("a.rs", "pub struct A; fn f() -> crate::b::B { todo!() }"),
        ("b.rs", "pub struct B; #[cfg(test)] mod tests;"),
        ("b/tests.rs", "use crate::a::A;"),
    ]);
    assert_eq!(looped.len(), 1, "{looped:?}");
    assert!(looped[0].contains("import loop among a, b"), "{looped:?}");
}

#[test]
fn the_crates_own_name_and_its_exported_macros_lead_to_their_modules() {
    // A crate that calls itself `mine` names its root `mine::` too.
    let looped = problems_of(&[
        ("lib.rs", "extern crate self as mine; mod a; mod b;"),
        ("a.rs", "pub struct A; fn f() -> mine::b::B { todo!() }"),
        ("b.rs", "pub struct B; fn f() -> crate::a::A { todo!() }"),
    ]);
    assert_eq!(looped.len(), 1, "{looped:?}");
    assert!(
        looped[0].starts_with("import loop among a, b:"),
        "{looped:?}"
    );
    // A macro exported at the root is the module's that defines it: naming it through
    // the root imports nothing from above.
    let problems = problems_of(&[
        ("lib.rs", "pub mod hub;"),
        ("hub/mod.rs", "mod m; mod user;"),
        ("hub/m.rs", "#[macro_export] macro_rules! made { () => {} }"),
        ("hub/user.rs", "crate::made!();"),
    ]);
    assert_eq!(problems, Vec::<String>::new());
}
