//! Where a node of the nested form is, named for people: the steps from the root, each a
//! slot and the node in it, as `Start > body: Body > wing: Wing` or
//! `Start > lots[3]: Lot`. A node whose type is not known yet ends its path with its
//! slot alone (`Start > body`); the root before its type is known is `tree`.

/// The places of the nodes read so far, each pointing to its parent's; a path is only
/// spelled out when an error needs it. O(1) a node.
#[derive(Default)]
pub(super) struct Places {
    places: Vec<Place>,
}

/// A node's place: index into [`Places`].
#[derive(Clone, Copy)]
pub(super) struct PlaceId(usize);

struct Place {
    parent: Option<PlaceId>,
    /// The slot the node hangs from, with its index in an array slot; `None` for the root.
    slot: Option<(&'static str, Option<u32>)>,
    /// The node's type, once known.
    node: Option<&'static str>,
}

impl Places {
    /// The root's place.
    pub(super) fn root(&mut self) -> PlaceId {
        self.push(Place {
            parent: None,
            slot: None,
            node: None,
        })
    }

    /// The place of a child of the node at `parent` in slot `slot` (at `index` in an
    /// array slot).
    pub(super) fn child(
        &mut self,
        parent: PlaceId,
        slot: &'static str,
        index: Option<u32>,
    ) -> PlaceId {
        self.push(Place {
            parent: Some(parent),
            slot: Some((slot, index)),
            node: None,
        })
    }

    /// Records that the node at `id` is of type `node`.
    pub(super) fn name(&mut self, id: PlaceId, node: &'static str) {
        self.places[id.0].node = Some(node);
    }

    /// The path of `id` from the root.
    pub(super) fn path(&self, id: PlaceId) -> String {
        let mut steps = Vec::new();
        let mut at = Some(id);
        while let Some(PlaceId(i)) = at {
            let place = &self.places[i];
            steps.push(match (place.slot, place.node) {
                (None, Some(node)) => node.to_owned(),
                (None, None) => "tree".to_owned(),
                (Some((slot, index)), node) => {
                    let mut step = slot.to_owned();
                    if let Some(i) = index {
                        step += &format!("[{i}]");
                    }
                    if let Some(node) = node {
                        step += &format!(": {node}");
                    }
                    step
                }
            });
            at = place.parent;
        }
        steps.reverse();
        steps.join(" > ")
    }

    fn push(&mut self, place: Place) -> PlaceId {
        self.places.push(place);
        PlaceId(self.places.len() - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::Places;

    #[test]
    fn paths_name_slots_indices_and_known_nodes() {
        let mut places = Places::default();
        let root = places.root();
        assert_eq!(places.path(root), "tree");
        places.name(root, "Start");
        let lot = places.child(root, "lots", Some(3));
        assert_eq!(places.path(lot), "Start > lots[3]");
        places.name(lot, "Lot");
        let building = places.child(lot, "building", None);
        places.name(building, "Building");
        assert_eq!(
            places.path(building),
            "Start > lots[3]: Lot > building: Building"
        );
    }
}
