//! Telling the two forms apart by their keys: the nested form has `tree` where the packed
//! form has `genes`, at the top of a genome or in each genome of a set's `genomes`.

use std::fmt;

use serde::Deserializer;
use serde::de::{DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};

/// Whether `json` is in the nested form: it has a `tree` key at the top or in a genome of
/// its `genomes`.
///
/// Keys are noted as they are read, so a text that goes wrong further on (bad JSON, or
/// nested deeper than JSON is read) is still told by the keys before the fault, and the
/// reader of its form explains the fault.
pub(super) fn is_nested(json: &str) -> bool {
    let mut nested = false;
    let mut de = serde_json::Deserializer::from_str(json);
    // A fault ends the reading; the keys seen before it decide.
    let _ = de.deserialize_map(Keys {
        nested: &mut nested,
        top: true,
    });
    nested
}

/// Notes a `tree` key of a genome object; at the top, looks into `genomes` too.
struct Keys<'a> {
    nested: &'a mut bool,
    top: bool,
}

impl<'de> Visitor<'de> for Keys<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a genome object")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while let Some(key) = map.next_key::<String>()? {
            if key == "tree" {
                *self.nested = true;
            }
            if self.top && key == "genomes" {
                map.next_value_seed(Genomes(&mut *self.nested))?;
            } else {
                map.next_value::<IgnoredAny>()?;
            }
        }
        Ok(())
    }
}

/// The `genomes` list of a set: notes a `tree` key in any of its genomes.
struct Genomes<'a>(&'a mut bool);

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
struct Genome<'a>(&'a mut bool);

impl<'de> DeserializeSeed<'de> for Genome<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_map(Keys {
            nested: self.0,
            top: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::is_nested;

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
