//! What a genome file holds, told by its top-level keys: the generator it names, whether
//! it is a set (`genomes`), and its form (the nested form has `tree` where the packed form
//! has `genes`, at the top of a genome or in each genome of a set's `genomes`).

use std::fmt;

use serde::Deserializer;
use serde::de::{DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};

/// What a genome file's JSON holds, told by its keys without reading its genomes: which
/// generator it names, whether it is a [set](super::GenomeSet), and whether it is in the
/// nested form.
///
/// Keys are noted as they are read, so a text that goes wrong further on (bad JSON, or
/// nested deeper than JSON is read) is still told by the keys before the fault, and the
/// reader of its form explains the fault.
///
/// ```
/// use shapegen_runtime::genome::JsonLayout;
///
/// let layout = JsonLayout::of(r#"{"generator": "tree", "genomes": [{"tree": {"node": "Start"}}]}"#);
/// assert_eq!(layout.generator.as_deref(), Some("tree"));
/// assert!(layout.set && layout.nested);
/// assert!(!JsonLayout::of(r#"{"generator": "tree", "genes": []}"#).nested);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct JsonLayout {
    /// The `generator` named at the top, when it is a string.
    pub generator: Option<String>,
    /// Whether the file is a set: `{"generator", "genomes": [...]}`.
    pub set: bool,
    /// Whether the file is in the nested form: a `tree` at the top or in a genome of a set.
    pub nested: bool,
}

impl JsonLayout {
    /// The layout of `json`, as far as its keys tell before any fault.
    pub fn of(json: &str) -> JsonLayout {
        let mut layout = JsonLayout::default();
        let mut de = serde_json::Deserializer::from_str(json);
        // A fault ends the reading; the keys seen before it decide.
        let _ = de.deserialize_map(Keys {
            layout: &mut layout,
            top: true,
        });
        layout
    }
}

/// Notes the keys of a genome object; at the top, the generator and the set's genomes too.
struct Keys<'a> {
    layout: &'a mut JsonLayout,
    top: bool,
}

impl<'de> Visitor<'de> for Keys<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a genome object")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "tree" => {
                    self.layout.nested = true;
                    map.next_value::<IgnoredAny>()?;
                }
                "generator" if self.top => {
                    let name = map.next_value::<serde_json::Value>()?;
                    self.layout.generator = name.as_str().map(str::to_owned);
                }
                "genomes" if self.top => {
                    self.layout.set = true;
                    map.next_value_seed(Genomes(&mut *self.layout))?;
                }
                _ => {
                    map.next_value::<IgnoredAny>()?;
                }
            }
        }
        Ok(())
    }
}

/// The `genomes` list of a set: notes a `tree` key in any of its genomes.
struct Genomes<'a>(&'a mut JsonLayout);

impl<'de> DeserializeSeed<'de> for Genomes<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for Genomes<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a list of genomes")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        while seq.next_element_seed(Genome(&mut *self.0))?.is_some() {}
        Ok(())
    }
}

/// One genome of a set's list.
struct Genome<'a>(&'a mut JsonLayout);

impl<'de> DeserializeSeed<'de> for Genome<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_map(Keys {
            layout: self.0,
            top: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::JsonLayout;

    fn is_nested(json: &str) -> bool {
        JsonLayout::of(json).nested
    }

    #[test]
    fn the_form_is_told_by_the_keys_before_any_fault() {
        assert!(is_nested(
            r#"{"generator": "G", "tree": {"node": "Start"}}"#
        ));
        assert!(!is_nested(r#"{"generator": "G", "genes": []}"#));
        assert!(is_nested(
            r#"{"genomes": [{"tree": null}], "generator": "G"}"#
        ));
        assert!(is_nested(r#"{"genomes": [{"genes": []}, {"tree": 1}]}"#));
        assert!(!is_nested(r#"{"genomes": [{"genes": []}, {"genes": []}]}"#));
        // A `tree` below the top is not a form's key.
        assert!(!is_nested(r#"{"genes": [{"params": {"tree": 1}}]}"#));
        // Faults after the key do not hide it; faults before it leave the packed form.
        assert!(is_nested(r#"{"generator": "G", "tree": {"node": ,}"#));
        assert!(!is_nested(r#"{"generator": , "tree": {}}"#));
        assert!(!is_nested("[1, 2]"));
        let deep = format!(r#"{{"tree": {}{}}}"#, "[".repeat(200), "]".repeat(200));
        assert!(is_nested(&deep));
    }
}
