//! Derivation: walking a genome from its root and running each node's rule, which emits
//! mesh instances and hands scopes to the node's children.
//!
//! The `generator!` macro implements [`Grammar`] for each grammar: one rule function per
//! node type and a `match` over node kinds that calls them. Rules see their scope as a
//! [`Shape`], their parameters as plain values and their children as [`Child`] (single
//! slots) or [`Slots`] (array slots).

use std::cell::{OnceCell, RefCell};
use std::marker::PhantomData;
use std::ops::Deref;

use glam::Vec3;
use typed_arena::Arena;

use crate::geometry::{
    Axis, Face, Inset, Instance, Margins, Mesh, MeshId, Part, Polygon, Roof, RoofError, RoofMeshes,
    RoofShape, Scope,
};
use crate::graph::{GeneratorGraph, HEADER_WORDS};
use crate::param::ParamValue;

mod site;

pub use site::Site;

/// A procedural generator: its static graph and its derivation rules.
///
/// Implemented by the `generator!` macro; there is no need to implement it by hand.
pub trait Grammar: Sized + Send + Sync + 'static {
    /// The grammar's generator graph.
    const GRAPH: &'static GeneratorGraph;

    /// Runs the rule of `gene`'s node type in `shape`.
    #[doc(hidden)]
    fn derive_gene<'a>(shape: Shape<'a, Self>, gene: GeneView<'a>);
}

/// The parameters of one node type, as the `generator!` macro declares them: a
/// `#[repr(C)]` struct of the node's parameters, named after the node.
pub trait NodeParams: Copy + 'static {
    /// The node type's kind: its index in the grammar's [`GeneratorGraph::nodes`].
    const KIND: u32;
    /// Number of child links in a gene of this node type.
    const LINKS: u32;
    /// Number of 32-bit words the parameters take.
    const WORDS: u32;
    /// Reads the parameters from a gene's parameter words.
    fn read(params: &[u32]) -> Self;
    /// Writes the parameters into a gene's parameter words.
    fn write(&self, params: &mut [u32]);
}

/// A node type's rule, run on a child whose parameters were read with it
/// ([`GeneView::child`]): the slot a child hangs on fixes its node type, so
/// [`Shape::derive`] runs the rule without looking the gene's kind up or reading its
/// parameters again. The `generator!` macro implements it for every node type; a rule
/// helper generic over the child's node type names it as a bound (`P: NodeRule<G>`).
pub trait NodeRule<G>: NodeParams {
    /// Runs the rule of this node type on `gene`, whose parameters are `params`, in
    /// `shape`.
    fn derive<'a>(shape: Shape<'a, G>, gene: GeneView<'a>, params: Self);
}

/// Reads a parameter of type `T` at word `offset` of a gene's parameter words.
#[doc(hidden)]
#[inline]
pub fn read_param<T: ParamValue>(params: &[u32], offset: usize) -> T {
    T::read(&params[offset..offset + T::WORDS])
}

/// Writes a parameter of type `T` at word `offset` of a gene's parameter words.
#[doc(hidden)]
#[inline]
pub fn write_param<T: ParamValue>(params: &mut [u32], offset: usize, value: T) {
    value.write(&mut params[offset..offset + T::WORDS]);
}

/// A read-only view of one gene inside a genome's words.
#[derive(Clone, Copy, Debug)]
pub struct GeneView<'a> {
    words: &'a [u32],
    pos: u32,
}

impl<'a> GeneView<'a> {
    /// The gene starting at word `pos` of `words`.
    #[inline]
    pub(crate) fn new(words: &'a [u32], pos: u32) -> Self {
        GeneView { words, pos }
    }

    /// Word position of the gene in its genome.
    #[inline]
    pub fn pos(&self) -> u32 {
        self.pos
    }

    /// Node kind of the gene.
    #[inline]
    pub fn kind(&self) -> u32 {
        self.words[self.pos as usize]
    }

    /// Word position of the parent gene, or `None` for the root.
    #[inline]
    pub fn parent(&self) -> Option<u32> {
        let off = self.words[self.pos as usize + 1] as i32;
        (off != 0).then(|| self.pos.wrapping_add_signed(off))
    }

    /// Word position of the child on link `link`, or `None` when that child is absent.
    #[inline]
    pub fn link(&self, link: u32) -> Option<u32> {
        let off = self.words[(self.pos + HEADER_WORDS + link) as usize] as i32;
        (off != 0).then(|| self.pos.wrapping_add_signed(off))
    }

    /// The gene's parameter words, given how many links its node type has.
    #[inline]
    pub fn params(&self, links: u32) -> &'a [u32] {
        &self.words[(self.pos + HEADER_WORDS + links) as usize..]
    }

    /// The child on link `link`, with its parameters read as `P`.
    #[inline(always)]
    pub fn child<P: NodeParams>(&self, link: u32) -> Option<Child<'a, P>> {
        self.link(link).map(|pos| {
            let gene = GeneView::new(self.words, pos);
            Child {
                gene,
                params: P::read(gene.params(P::LINKS)),
            }
        })
    }
}

/// A present child of the node being derived: its parameters (reachable by `Deref`, so
/// `child.size` reads the child's `size`) and the gene to derive it from with
/// [`Shape::derive`].
#[derive(Clone, Copy, Debug)]
pub struct Child<'a, P> {
    gene: GeneView<'a>,
    params: P,
}

impl<P> Child<'_, P> {
    /// The child's parameters.
    #[inline]
    pub fn params(&self) -> &P {
        &self.params
    }
}

impl<P> Deref for Child<'_, P> {
    type Target = P;
    #[inline]
    fn deref(&self) -> &P {
        &self.params
    }
}

/// An array slot `[Node; N]` of the node being derived: `N` links, each holding a child
/// or not.
#[derive(Clone, Copy, Debug)]
pub struct Slots<'a, P, const N: usize> {
    gene: GeneView<'a>,
    first_link: u32,
    _p: PhantomData<fn() -> P>,
}

impl<'a, P: NodeParams, const N: usize> Slots<'a, P, N> {
    #[doc(hidden)]
    #[inline]
    pub fn new(gene: GeneView<'a>, first_link: u32) -> Self {
        Slots {
            gene,
            first_link,
            _p: PhantomData,
        }
    }

    /// The child in slot `index`, if `index < N` and that child is present.
    #[inline]
    pub fn get(&self, index: usize) -> Option<Child<'a, P>> {
        (index < N).then(|| self.gene.child(self.first_link + index as u32))?
    }

    /// The present children with their slot indices, in slot order.
    pub fn iter(&self) -> impl Iterator<Item = (usize, Child<'a, P>)> + 'a {
        let this = *self;
        (0..N).filter_map(move |i| this.get(i).map(|c| (i, c)))
    }

    /// Number of slots, present or not: `N`.
    #[inline]
    pub const fn len(&self) -> usize {
        N
    }

    /// Whether the array has no slots at all (`N == 0`).
    #[inline]
    pub const fn is_empty(&self) -> bool {
        N == 0
    }
}

/// The state shared by all rules during one derivation: the site it grows on, the
/// output instances and the footprints its rules made.
pub struct Derivation<'s> {
    out: RefCell<Vec<Instance>>,
    site: &'s Site,
    /// Made when a rule first makes a footprint: a derivation that makes none
    /// allocates nothing for them.
    footprints: OnceCell<Arena<Polygon>>,
}

impl std::fmt::Debug for Derivation<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Derivation")
            .field("out", &self.out)
            .field("site", &self.site)
            .finish_non_exhaustive()
    }
}

impl Derivation<'_> {
    /// Derives the genome held in `words` (root at word 0) on `site`, appending its
    /// instances to `out`.
    pub(crate) fn run<G: Grammar>(words: &[u32], site: &Site, out: &mut Vec<Instance>) {
        let ctx = Derivation {
            out: RefCell::new(std::mem::take(out)),
            site,
            footprints: OnceCell::new(),
        };
        let shape = Shape {
            scope: Scope::UNIT,
            footprint: None,
            ctx: &ctx,
            _g: PhantomData,
        };
        G::derive_gene(shape, GeneView::new(words, 0));
        *out = ctx.out.into_inner();
    }
}

/// The scope a rule works in, tied to the derivation it belongs to: [`Scope`]'s
/// operations plus [`emit`](Self::emit) and [`derive`](Self::derive), and the footprint
/// it builds on, if a rule gave it one ([`on_footprint`](Self::on_footprint)), which
/// every scope operation keeps.
#[derive(Debug)]
pub struct Shape<'a, G> {
    scope: Scope,
    footprint: Option<&'a Polygon>,
    ctx: &'a Derivation<'a>,
    _g: PhantomData<fn() -> G>,
}

impl<G> Clone for Shape<'_, G> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<G> Copy for Shape<'_, G> {}

/// Forwards scope operations that return a new scope to [`Shape`].
macro_rules! forward_scope_ops {
    ($($(#[$doc:meta])* fn $name:ident($($arg:ident: $ty:ty),*);)*) => {
        $(
            $(#[$doc])*
            #[inline]
            pub fn $name(self, $($arg: $ty),*) -> Self {
                self.with_scope(self.scope.$name($($arg),*))
            }
        )*
    };
}

impl<'a, G: Grammar> Shape<'a, G> {
    /// The plain scope.
    #[inline]
    pub fn scope(&self) -> Scope {
        self.scope
    }

    /// The site the derivation grows on: [`Site::NONE`] unless the model is derived on
    /// one ([`Genome::derive_on`](crate::Genome::derive_on)).
    #[inline]
    pub fn site(&self) -> &'a Site {
        self.ctx.site
    }

    /// The footprint the shape builds on, in the plane of its box's bottom face (see
    /// [`Scope::extrude_polygon`]): `None` until a rule sets one.
    #[inline]
    pub fn footprint(&self) -> Option<&'a Polygon> {
        self.footprint
    }

    /// The same shape building on `footprint`: the site's lot, say, or a footprint the
    /// grammar keeps in a static.
    ///
    /// ```
    /// use std::sync::LazyLock;
    /// use glam::vec2;
    /// use shapegen_runtime::geometry::Polygon;
    /// use shapegen_runtime::prelude::*;
    ///
    /// static SQUARE: LazyLock<Polygon> =
    ///     LazyLock::new(|| Polygon::rectangle(vec2(4.0, 4.0)).expect("a square"));
    ///
    /// generator! {
    ///     /// A slab on the site's lot, or on a square without one, set back once.
    ///     pub Slab {
    ///         axiom Ground;
    ///         meshes { FACET = "facet" }
    ///         node Ground {
    ///             derive(s) {
    ///                 let s = s.on_footprint(s.site().lot().unwrap_or(&SQUARE));
    ///                 let inner = s.setback(1.0).expect("a 4-wide square has room for it");
    ///                 let area = inner.footprint().map(Polygon::area);
    ///                 assert_eq!(area, Some(4.0));
    ///                 inner.extrude_polygon(inner.footprint().unwrap(), 1.0, FACET);
    ///             }
    ///         }
    ///     }
    /// }
    ///
    /// let mut instances = Vec::new();
    /// Genome::<Slab>::with_root(Ground {})?.derive_into(&mut instances);
    /// assert_eq!(instances.len(), 12);
    /// # Ok::<(), shapegen_runtime::GenomeError>(())
    /// ```
    #[inline]
    pub fn on_footprint(self, footprint: &'a Polygon) -> Self {
        Shape {
            footprint: Some(footprint),
            ..self
        }
    }

    /// The same shape building on `footprint`, a polygon made by the rule, which the
    /// derivation keeps until it ends.
    pub fn on_new_footprint(self, footprint: Polygon) -> Self {
        let footprints = self.ctx.footprints.get_or_init(Arena::new);
        self.on_footprint(footprints.alloc(footprint))
    }

    /// CGA's `setback` to the remainder: the same shape on its footprint with every
    /// edge moved inward by `distance`, or `None` where the shape has no footprint, the
    /// distance is not positive and finite, or the moved outline is no longer a polygon
    /// of the same edges (a part narrower than twice the distance closes): the
    /// [`Polygon::offset`] by `-distance`, the remainder of [`Polygon::setback`] without
    /// its strips.
    pub fn setback(self, distance: f32) -> Option<Self> {
        if !(distance > 0.0 && distance.is_finite()) {
            return None;
        }
        let inner = self.footprint?.offset(-f64::from(distance))?;
        Some(self.on_new_footprint(inner))
    }

    /// The same shape on its footprint with each edge `i` moved inward by its own
    /// `distance(i)` (a street setback on the front, say), or `None` where the shape has
    /// no footprint or the moved outline is not a polygon of the same edges; see
    /// [`Polygon::offset_edges`].
    pub fn setback_edges(self, distance: impl Fn(usize) -> f32) -> Option<Self> {
        let inner = self.footprint?.offset_edges(|i| f64::from(distance(i)))?;
        Some(self.on_new_footprint(inner))
    }

    /// The same derivation with another scope.
    #[inline]
    pub fn with_scope(self, scope: Scope) -> Self {
        Shape { scope, ..self }
    }

    /// The box's size along its local axes.
    #[inline]
    pub fn size(&self) -> Vec3 {
        self.scope.size()
    }

    forward_scope_ops! {
        /// Moves the box along its own axes; see [`Scope::translate`].
        fn translate(v: Vec3);
        /// Rotates the box about its own `axis`; see [`Scope::rotate`].
        fn rotate(axis: Vec3, angle: f32);
        /// Rotates the box about its own x axis; see [`Scope::rotate_x`].
        fn rotate_x(angle: f32);
        /// Rotates the box about its own y axis; see [`Scope::rotate_y`].
        fn rotate_y(angle: f32);
        /// Rotates the box about its own z axis; see [`Scope::rotate_z`].
        fn rotate_z(angle: f32);
        /// Multiplies the size component-wise; see [`Scope::resize`].
        fn resize(factor: Vec3);
        /// Sets the size; see [`Scope::with_size`].
        fn with_size(size: Vec3);
        /// The flat scope of one face of the box; see [`Scope::face`].
        fn face(face: Face);
        /// Sets the depth, keeping the back plane; see [`Scope::extrude`].
        fn extrude(depth: f32);
    }

    /// Splits the box along `axis`, one shape per part; see [`Scope::split`].
    #[inline]
    pub fn split(self, axis: Axis, parts: &[Part]) -> impl ExactSizeIterator<Item = Self> {
        self.scope
            .split(axis, parts)
            .map(move |s| self.with_scope(s))
    }

    /// Splits the box along `axis` into equal tiles of about `tile`; see
    /// [`Scope::repeat`].
    #[inline]
    pub fn repeat(self, axis: Axis, tile: f32) -> impl ExactSizeIterator<Item = Self> {
        self.scope
            .repeat(axis, tile)
            .map(move |s| self.with_scope(s))
    }

    /// The six faces of the box with their flat shapes; see [`Scope::faces`].
    #[inline]
    pub fn faces(self) -> impl ExactSizeIterator<Item = (Face, Self)> {
        self.scope
            .faces()
            .map(move |(f, s)| (f, self.with_scope(s)))
    }

    /// Emits `mesh` scaled to fill the box.
    #[inline]
    pub fn emit(&self, mesh: MeshId) {
        self.push(Instance {
            transform: self.scope.transform(),
            mesh,
        });
    }

    /// Emits `mesh` at the box's frame without scaling it to the box's size.
    #[inline]
    pub fn emit_unscaled(&self, mesh: MeshId) {
        self.push(Instance {
            transform: self.scope.frame(),
            mesh,
        });
    }

    /// Emits the roof of `shape` with `overhang` on the top of the box, as instances of
    /// the grammar's roof pieces; see [`Scope::roof`]. A measure out of range emits
    /// nothing and says why.
    pub fn roof(
        &self,
        shape: RoofShape,
        overhang: f32,
        meshes: &RoofMeshes,
    ) -> Result<(), RoofError> {
        self.scope
            .roof(shape, overhang, meshes, &mut self.ctx.out.borrow_mut())
    }

    /// Emits `mesh`, given in the box's frame without scaling, as generated geometry:
    /// one instance of the facet mesh `facet` per triangle; see [`Scope::surface`] and
    /// [`geometry::facet_transform`](crate::geometry::facet_transform).
    pub fn emit_surface(&self, mesh: &Mesh, facet: MeshId) -> usize {
        self.scope
            .surface(mesh, facet, &mut self.ctx.out.borrow_mut())
    }

    /// Emits the prism of `height` standing on `footprint` on the bottom of the box, as
    /// facets (CGA's `extrude` of a polygon); see [`Scope::extrude_polygon`].
    pub fn extrude_polygon(&self, footprint: &Polygon, height: f32, facet: MeshId) -> usize {
        self.scope
            .extrude_polygon(footprint, height, facet, &mut self.ctx.out.borrow_mut())
    }

    /// Emits the roof of `shape` with `overhang` over `footprint` on the top of the box,
    /// as facets (a straight-skeleton roof on any simple polygon); see
    /// [`Scope::roof_polygon`]. A measure out of range emits nothing and says why.
    pub fn roof_polygon(
        &self,
        footprint: &Polygon,
        shape: RoofShape,
        overhang: f32,
        facet: MeshId,
    ) -> Result<Roof, RoofError> {
        self.scope.roof_polygon(
            footprint,
            shape,
            overhang,
            facet,
            &mut self.ctx.out.borrow_mut(),
        )
    }

    /// Emits the box's front rectangle (a flat shape's own plane) as two facets of
    /// `facet` facing its `+z`; see [`Scope::emit_rect`]. Returns how many.
    ///
    /// With [`walls`](Self::walls), [`top_cap`](Self::top_cap),
    /// [`bottom_cap`](Self::bottom_cap) and [`inset`](Self::inset), rules build CGA's
    /// facades as closed solids: a footprint's walls, each split into floors and
    /// tiles (splits and repeats tile flat shapes along `x` and `y`), each tile a
    /// window or a door recessed into the wall.
    ///
    /// ```
    /// # use rand::SeedableRng;
    /// use shapegen_runtime::geometry::{Margins, Polygon};
    /// use shapegen_runtime::prelude::*;
    ///
    /// generator! {
    ///     pub Block {
    ///         axiom Lot;
    ///         meshes {
    ///             WALL = "wall",
    ///             WINDOW = "window",
    ///             DOOR = "door",
    ///         }
    ///         node Lot {
    ///             derive(s) {
    ///                 let footprint = Polygon::rectangle(vec2(12.0, 8.0)).unwrap();
    ///                 let lot = s.with_size(vec3(12.0, 9.0, 8.0));
    ///                 for (face, wall) in lot.walls(&footprint, 9.0) {
    ///                     if face != Face::Front {
    ///                         wall.emit_rect(WALL);
    ///                         continue;
    ///                     }
    ///                     // 12 x 9: three floors of four tiles, a door on the ground.
    ///                     for (floor, level) in wall.repeat(Axis::Y, 3.0).enumerate() {
    ///                         for (k, tile) in level.repeat(Axis::X, 3.0).enumerate() {
    ///                             let door = floor == 0 && k == 1;
    ///                             let (margins, opening) = if door {
    ///                                 (Margins::door(0.8, 0.6), DOOR)
    ///                             } else {
    ///                                 (Margins::new(0.75, 0.75, 0.8, 0.6), WINDOW)
    ///                             };
    ///                             let inset = tile.inset(margins, 0.3).unwrap();
    ///                             for part in inset.frame.into_iter().chain(inset.reveals) {
    ///                                 part.emit_rect(WALL);
    ///                             }
    ///                             inset.opening.emit_rect(opening);
    ///                         }
    ///                     }
    ///                 }
    ///                 lot.top_cap(&footprint, 9.0, WALL);
    ///                 lot.bottom_cap(&footprint, WALL);
    ///             }
    ///         }
    ///     }
    /// }
    ///
    /// let genome = Genome::<Block>::axiom(&mut rand_chacha::ChaCha8Rng::seed_from_u64(1));
    /// let mut out = Vec::new();
    /// genome.derive_into(&mut out);
    /// let count = |mesh: MeshId| out.iter().filter(|i| i.mesh == mesh).count();
    /// assert_eq!((count(WINDOW), count(DOOR)), (2 * 11, 2));
    /// // Three plain walls, twelve tiles of 4 frame strips and 4 reveals (the door's
    /// // bottom strip is empty), two caps.
    /// assert_eq!(count(WALL), 3 * 2 + 12 * 8 * 2 - 2 + 2 * 2);
    /// ```
    pub fn emit_rect(&self, facet: MeshId) -> usize {
        self.scope.emit_rect(facet, &mut self.ctx.out.borrow_mut())
    }

    /// CGA's `comp(f)` of the prism of `height` on `footprint` on the bottom of the box:
    /// one flat shape per footprint edge, facing out, with the face of the box it
    /// faces; see [`Scope::walls`]. See [`emit_rect`](Self::emit_rect) for an example.
    pub fn walls(
        self,
        footprint: &Polygon,
        height: f32,
    ) -> impl ExactSizeIterator<Item = (Face, Self)> {
        self.scope
            .walls(footprint, height)
            .map(move |(f, s)| (f, self.with_scope(s)))
    }

    /// Emits the top of the prism of `height` on `footprint`, facing up, as facets; see
    /// [`Scope::top_cap`]. Returns how many.
    pub fn top_cap(&self, footprint: &Polygon, height: f32, facet: MeshId) -> usize {
        self.scope
            .top_cap(footprint, height, facet, &mut self.ctx.out.borrow_mut())
    }

    /// Emits the bottom of the prism on `footprint`, facing down, as facets; see
    /// [`Scope::bottom_cap`]. Returns how many.
    pub fn bottom_cap(&self, footprint: &Polygon, facet: MeshId) -> usize {
        self.scope
            .bottom_cap(footprint, facet, &mut self.ctx.out.borrow_mut())
    }

    /// CGA's `inset` of a window or a door into a flat tile: the frame, reveals and
    /// opening as shapes, or `None` when the margins leave no opening or a measure is
    /// negative or not finite; see [`Scope::inset`]. See
    /// [`emit_rect`](Self::emit_rect) for an example.
    pub fn inset(self, margins: Margins, depth: f32) -> Option<Inset<Self>> {
        let inset = self.scope.inset(margins, depth)?;
        Some(inset.map(|s| self.with_scope(s)))
    }

    #[inline]
    fn push(&self, instance: Instance) {
        self.ctx.out.borrow_mut().push(instance);
    }

    /// Runs `child`'s rule in this scope. A child may be derived more than once, in
    /// different scopes (a mirrored pair of wings from one gene, say).
    #[inline]
    pub fn derive<P: NodeRule<G>>(self, child: Child<'a, P>) {
        debug_assert_eq!(
            child.gene.kind(),
            P::KIND,
            "a child of its slot's node type"
        );
        P::derive(self, child.gene, child.params);
    }

    /// Runs, in this scope and in link order, the rule of every child present on the
    /// first `links` links of `gene`: the rule of a node declared without `derive`.
    #[doc(hidden)]
    #[inline]
    pub fn derive_children(self, gene: GeneView<'a>, links: u32) {
        for link in 0..links {
            if let Some(pos) = gene.link(link) {
                G::derive_gene(self, GeneView::new(gene.words, pos));
            }
        }
    }
}

#[cfg(test)]
mod tests;
