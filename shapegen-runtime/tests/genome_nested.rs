//! The nested JSON form of genomes: round trips with the packed form for every published
//! generator, a hand-written genome, the exact layout, and every mistake it can hold,
//! named by the node's path.

mod support {
    pub mod city_expanded;
    pub mod known;
    pub mod spaceship_expanded;
}

use generators::{GeneratorVisitor, Published};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::error_chain;
use shapegen_runtime::genome::{Genome, GenomeSet, JsonError, Limits};
use shapegen_runtime::graph::HEADER_WORDS;
use shapegen_runtime::ops::Operators;
use shapegen_runtime::{Grammar, Instance};
use support::city_expanded::{self as city, City};
use support::known::{ship, small, town};
use support::spaceship_expanded::{Body, Spaceship, Start};

/// The words of `g` laid out in pre-order, children in link order: the layout reading the
/// nested form gives, built here by its own recursion over the links.
fn preorder<G: Grammar>(g: &Genome<G>) -> Vec<u32> {
    fn copy<G: Grammar>(words: &[u32], pos: u32, parent: Option<(u32, u32)>, out: &mut Vec<u32>) {
        let node = G::GRAPH.node(words[pos as usize]).unwrap();
        let at = out.len() as u32;
        out.extend_from_slice(&words[pos as usize..][..node.gene_words() as usize]);
        out[at as usize + 1] = match parent {
            Some((p, link)) => {
                out[(p + HEADER_WORDS + link) as usize] = at - p;
                (p as i32 - at as i32) as u32
            }
            None => 0,
        };
        let links = (at + HEADER_WORDS) as usize..(at + HEADER_WORDS + node.links) as usize;
        out[links].fill(0);
        for link in 0..node.links {
            let offset = words[(pos + HEADER_WORDS + link) as usize];
            if offset != 0 {
                copy::<G>(words, pos + offset, Some((at, link)), out);
            }
        }
    }
    let mut out = Vec::new();
    copy::<G>(g.words(), 0, None, &mut out);
    out
}

fn derived<G: Grammar>(g: &Genome<G>) -> Vec<Instance> {
    let mut out = Vec::new();
    g.derive_into(&mut out);
    out
}

/// Random genomes of one grammar through the nested form and back, alone and as a set.
struct RoundTrip;

impl GeneratorVisitor for RoundTrip {
    type Output = ();

    fn visit<G: Grammar>(self, limits: Limits) {
        let name = G::GRAPH.name;
        let mut ops = Operators::<G>::new(limits).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        let mut genomes: Vec<Genome<G>> = (0..30)
            .map(|i| ops.random(limits.max_len * (i % 3 + 1) / 4, &mut rng))
            .collect();
        genomes.extend((0..10).map(|_| ops.sample(&mut rng)));
        let mut laid_out_otherwise = 0;
        let mut read = Vec::new();
        for (i, g) in genomes.iter().enumerate() {
            let nested = g.to_nested_json();
            let back = Genome::<G>::from_json(&nested)
                .unwrap_or_else(|e| panic!("{name} genome {i}: {e}\n{nested}"));
            assert_eq!(back.words(), preorder(g), "{name} genome {i}");
            assert_eq!(back.len(), g.len());
            assert_eq!(derived(&back), derived(g), "{name} genome {i}");
            if back != *g {
                laid_out_otherwise += 1;
            }
            // From here on the layout is the nested form's: both forms give it back word for
            // word, and each writes the same text again.
            assert_eq!(back.to_nested_json(), nested, "{name} genome {i}");
            let packed = back.to_json();
            let again = Genome::<G>::from_json(&packed).unwrap();
            assert_eq!(again, back);
            let through_nested = Genome::<G>::from_json(&again.to_nested_json()).unwrap();
            assert_eq!(through_nested.words(), back.words());
            assert_eq!(through_nested.to_json(), packed);
            read.push(back);
        }
        assert!(
            laid_out_otherwise > 0,
            "{name}: no genome exercised the relayout"
        );

        let set = GenomeSet::new(genomes);
        let nested = set.to_nested_json();
        let back = GenomeSet::<G>::from_json(&nested).unwrap();
        assert_eq!(back.genomes, read, "{name} set");
        assert_eq!(back.to_nested_json(), nested);
        let packed = GenomeSet::<G>::from_json(&back.to_json()).unwrap();
        assert_eq!(packed, back);
    }
}

#[test]
fn random_genomes_of_every_published_generator_round_trip() {
    for generator in Published::ALL {
        generator.visit(RoundTrip);
    }
}

#[test]
fn a_hand_written_spaceship_loads_and_derives() {
    use generators::spaceship::{self, Spaceship};
    let json = r#"{
      "generator": "Spaceship",
      "tree": {"node": "Start", "children": {
        "body": {"node": "Body", "params": {"size": [1.2, 1.0, 1.4]}, "children": {
          "next": {"node": "Body", "params": {"size": [0.8, 0.9, 1.0]}, "children": {
            "top": {"node": "Top", "params": {"size": [0.5, 0.15, 0.5]}}
          }},
          "wing": {"node": "Wing", "params": {"size": [0.6, 0.3, 0.7], "shift": -0.2},
                   "children": {"next": {"node": "WingNext",
                                         "params": {"size": [0.9, 0.95, 1.0], "shift": 0.1}}}}
        }}
      }}
    }"#;
    let g = Genome::<Spaceship>::from_json(json).unwrap();
    // The same tree built in pre-order with the builder.
    let v3 = glam::Vec3::new;
    let mut built = Genome::<Spaceship>::with_root(spaceship::Start {}).unwrap();
    let body = built
        .attach(
            0,
            "body",
            spaceship::Body {
                size: v3(1.2, 1.0, 1.4),
            },
        )
        .unwrap();
    let next = built
        .attach(
            body,
            "next",
            spaceship::Body {
                size: v3(0.8, 0.9, 1.0),
            },
        )
        .unwrap();
    built
        .attach(
            next,
            "top",
            spaceship::Top {
                size: v3(0.5, 0.15, 0.5),
            },
        )
        .unwrap();
    let wing = built
        .attach(
            body,
            "wing",
            spaceship::Wing {
                size: v3(0.6, 0.3, 0.7),
                shift: -0.2,
            },
        )
        .unwrap();
    built
        .attach(
            wing,
            "next",
            spaceship::WingNext {
                size: v3(0.9, 0.95, 1.0),
                shift: 0.1,
            },
        )
        .unwrap();
    assert_eq!(g, built);
    assert_eq!(g.len(), 6);
    // Two hull boxes and a tower box, one each; the wing and its next box, a mirrored
    // pair each.
    assert_eq!(derived(&g).len(), 2 + 1 + 2 * 2);
}

#[test]
fn the_nested_form_is_laid_out_for_reading() {
    assert_eq!(
        small().to_nested_json(),
        r#"{
  "generator": "spaceship",
  "tree": {
    "node": "Start",
    "children": {
      "body": {
        "node": "Body",
        "params": {"size": [0.83, 1.2, 0.7]},
        "children": {
          "wing": {"node": "Wing", "params": {"size": [0.5, 0.3, 0.7], "shift": 0.1}}
        }
      }
    }
  }
}
"#
    );
    // An array slot stops at its last child; runs of empty entries share a line.
    let town = town();
    let json = town.to_nested_json();
    assert_eq!(
        json,
        r#"{
  "generator": "city",
  "tree": {
    "node": "Start",
    "children": {
      "lots": [
        null, null, null,
        {
          "node": "Lot",
          "children": {
            "building": {
              "node": "Building",
              "params": {"footprint": [1.0, 1.5], "height": 4.0, "rotation": 0.5235988, "style": 2, "floors": -1, "lit": true, "block": 3},
              "children": {
                "roof": {
                  "node": "Roof",
                  "params": {"pitch": 0.3},
                  "children": {
                    "spire": {"node": "Roof", "params": {"pitch": 0.9}}
                  }
                }
              }
            }
          }
        },
        null, null, null, null, null, null,
        {
          "node": "Lot",
          "children": {
            "building": {"node": "Building", "params": {"footprint": [1.0, 1.5], "height": 7.0, "rotation": 0.5235988, "style": 2, "floors": -1, "lit": true, "block": 3}}
          }
        }
      ]
    }
  }
}
"#
    );
    // `town` was built in pre-order, so it comes back word for word.
    assert_eq!(Genome::<City>::from_json(&json).unwrap(), town);
    // Long runs of empty entries go ten to a line.
    let mut far = Genome::<City>::with_root(city::Start {}).unwrap();
    far.attach_at(0, "lots", 12, city::Lot {}).unwrap();
    let json = far.to_nested_json();
    let nulls = "null, null, null, null, null, null, null, null, null, null";
    assert!(
        json.contains(&format!(
            "\"lots\": [\n        {nulls},\n        null, null,\n        {{\"node\": \"Lot\"}}\n      ]"
        )),
        "{json}"
    );
    assert_eq!(Genome::<City>::from_json(&json).unwrap(), far);

    let set = GenomeSet::new(vec![small(), Genome::with_root(Start {}).unwrap()]);
    assert_eq!(
        set.to_nested_json(),
        r#"{
  "generator": "spaceship",
  "genomes": [
    {
      "tree": {
        "node": "Start",
        "children": {
          "body": {
            "node": "Body",
            "params": {"size": [0.83, 1.2, 0.7]},
            "children": {
              "wing": {"node": "Wing", "params": {"size": [0.5, 0.3, 0.7], "shift": 0.1}}
            }
          }
        }
      }
    },
    {
      "tree": {"node": "Start"}
    }
  ]
}
"#
    );
    let empty = GenomeSet::<Spaceship>::new(Vec::new());
    assert_eq!(
        empty.to_nested_json(),
        "{\n  \"generator\": \"spaceship\",\n  \"genomes\": []\n}\n"
    );
    assert_eq!(
        GenomeSet::<Spaceship>::from_json(&empty.to_nested_json())
            .unwrap()
            .genomes
            .len(),
        0
    );
}

#[test]
fn array_slots_take_short_lists_nulls_and_any_order_of_keys() {
    let lot = |height: f32| {
        format!(
            r#"{{"node": "Lot", "children": {{"building": {{"node": "Building", "params": {{
                "footprint": [1.0, 1.5], "height": {height}, "rotation": 0.5235988, "style": 2,
                "floors": -1, "lit": true, "block": 3}},
                "children": {{"roof": null}}}}}}}}"#
        )
    };
    // Keys in any order, a trailing null, and a list shorter than the array.
    let json = format!(
        r#"{{"tree": {{"children": {{"lots": [null, null, null, {}, null, null, null, null, null, null, {}, null]}}, "node": "Start"}}, "generator": "City"}}"#,
        lot(4.0).replace(
            r#""roof": null"#,
            r#""roof": {"params": {"pitch": 0.3}, "node": "Roof", "children": {"spire": {"node": "Roof", "params": {"pitch": 0.9}}}}"#
        ),
        lot(7.0)
    );
    assert_eq!(Genome::<City>::from_json(&json).unwrap(), town());
    // An empty array slot may be null, an empty list, or left out.
    for lots in [r#""lots": null"#, r#""lots": []"#, ""] {
        let json = format!(
            r#"{{"generator": "City", "tree": {{"node": "Start", "children": {{{lots}}}}}}}"#
        );
        let g = Genome::<City>::from_json(&json).unwrap();
        assert_eq!(g.len(), 1, "{json}");
    }
    // A list of exactly the array's length fills its last index.
    let mut entries = vec!["null".to_owned(); 99];
    entries.push(r#"{"node": "Lot"}"#.to_owned());
    let json = format!(
        r#"{{"generator": "City", "tree": {{"node": "Start", "children": {{"lots": [{}]}}}}}}"#,
        entries.join(", ")
    );
    let g = Genome::<City>::from_json(&json).unwrap();
    assert_eq!(g.root().link(99), Some(102));
}

/// `small()`'s nested form, on one line, with `from` replaced by `to`.
fn tampered(from: &str, to: &str) -> String {
    let json = r#"{"generator": "spaceship", "tree": {"node": "Start", "children": {"body": {"node": "Body", "params": {"size": [0.83, 1.2, 0.7]}, "children": {"wing": {"node": "Wing", "params": {"size": [0.5, 0.3, 0.7], "shift": 0.1}}}}}}}"#;
    assert_eq!(Genome::<Spaceship>::from_json(json).unwrap(), small());
    assert!(json.contains(from), "{from} not in {json}");
    json.replacen(from, to, 1)
}

fn load_err(json: &str) -> String {
    Genome::<Spaceship>::from_json(json)
        .map_err(|e| error_chain(&e))
        .unwrap_err()
}

const SHIP_NODES: &str = "`Start`, `Body`, `Top`, `TopNext`, `Wing`, `WingNext`";

#[test]
fn every_mistake_is_named_by_the_node_path() {
    let cases = [
        (
            tampered(r#""generator": "spaceship""#, r#""generator": "city""#),
            "the genome is of generator `city`, but is being read as `spaceship` (also written `Spaceship`)".to_owned(),
        ),
        (
            tampered(r#""node": "Wing""#, r#""node": "Wong""#),
            format!(
                "at `Start > body: Body > wing`: `Wong` is not a node of `Spaceship`; its nodes \
                 are: {SHIP_NODES}"
            ),
        ),
        (
            tampered(r#""node": "Start""#, r#""node": "Strat""#),
            format!("at `tree`: `Strat` is not a node of `Spaceship`; its nodes are: {SHIP_NODES}"),
        ),
        (
            tampered(r#""node": "Wing""#, r#""node": "Top""#),
            "at `Start > body: Body > wing`: slot `wing` of `Body` holds `Wing` nodes, not `Top`"
                .to_owned(),
        ),
        (
            r#"{"generator": "Spaceship", "tree": {"node": "Body", "params": {"size": [1, 1, 1]}}}"#
                .to_owned(),
            "at `tree`: the root must be the axiom `Start`, not `Body`".to_owned(),
        ),
        (
            tampered(r#""wing": {"#, r#""nose": {"#),
            "at `Start > body: Body`: `nose` is not a slot of `Body`; its slots are: `next`, \
             `wing`, `top`"
                .to_owned(),
        ),
        (
            tampered(r#""wing": {"#, r#""wing": [{"#).replacen("0.1}}", "0.1}}]", 1),
            "at `Start > body: Body`: slot `wing` of `Body` holds one node or null, not a list"
                .to_owned(),
        ),
        (
            tampered(r#", "shift": 0.1"#, ""),
            "at `Start > body: Body > wing: Wing`: parameter `shift` (f32) is missing".to_owned(),
        ),
        (
            tampered(r#""shift": 0.1"#, r#""shift": 0.1, "tilt": 3"#),
            "at `Start > body: Body > wing: Wing`: `tilt` is not a parameter of `Wing`; its \
             parameters are: `size`, `shift`"
                .to_owned(),
        ),
        (
            tampered(r#""shift": 0.1"#, r#""shift": "left""#),
            "at `Start > body: Body > wing: Wing`: parameter `shift` must be a number (f32), not \
             `\"left\"`"
                .to_owned(),
        ),
        (
            tampered("[0.83, 1.2, 0.7]", "[0.83, 1.2]"),
            "at `Start > body: Body`: parameter `size` must be an array of 3 numbers (Vec3), not \
             `[0.83,1.2]`"
                .to_owned(),
        ),
        (
            tampered(r#""shift": 0.1"#, r#""shift": 0.6"#),
            "at `Start > body: Body > wing: Wing`: parameter `shift`: 0.6 is outside [-0.5, 0.5]"
                .to_owned(),
        ),
        (
            tampered(r#""params": {"size": [0.83, 1.2, 0.7]}, "#, ""),
            "at `Start > body: Body`: parameter `size` (Vec3) is missing".to_owned(),
        ),
        (
            tampered(r#""params": {"size": [0.83, 1.2, 0.7]}"#, r#""params": [0.83, 1.2, 0.7]"#),
            "at `Start > body: Body`: `params` must be an object of parameter values by name, \
             not `[0.83,1.2,0.7]`"
                .to_owned(),
        ),
        (
            tampered(r#""children": {"wing""#, r#""children": [{"wing""#).replacen(
                "0.1}}}",
                "0.1}}}]",
                1,
            ),
            "at `Start > body: Body`: `children` must be an object of child nodes by slot name, \
             not `[{\"wing\":{\"node\":\"Wing\",\"params\":{\"shift\":0.1,\"size\":[0.5,0....`"
                .to_owned(),
        ),
        (
            tampered(r#""node": "Wing", "#, ""),
            "at `Start > body: Body > wing`: the node does not name its type; give it as \
             `\"node\": \"Wing\"`"
                .to_owned(),
        ),
        (
            tampered(r#""node": "Wing""#, r#""node": 4"#),
            "at `Start > body: Body > wing`: `node` must be the name of a node type, as a \
             string, not `4`"
                .to_owned(),
        ),
        (
            tampered(r#""node": "Wing""#, r#""node": "Wing", "param": {}"#),
            "at `Start > body: Body > wing`: `param` is not a key of a node; a node has `node`, \
             `params` and `children`"
                .to_owned(),
        ),
        (
            r#"{"generator": "Spaceship", "tree": {"node": "Start", "children": {"body": 3}}}"#
                .to_owned(),
            "at `Start > body`: a node is an object with its type's name in `node` and, when it \
             has any, its `params` and `children`; found `3`"
                .to_owned(),
        ),
        (
            r#"{"generator": "Spaceship", "tree": null}"#.to_owned(),
            "at `tree`: a node is an object with its type's name in `node` and, when it has any, \
             its `params` and `children`; found `null`"
                .to_owned(),
        ),
    ];
    for (json, msg) in &cases {
        assert_eq!(&load_err(json), msg, "for {json}");
    }
    // Keys of the whole are checked by serde, with the place in the text.
    let err = load_err(&tampered(
        r#""generator": "spaceship""#,
        r#""generator": "spaceship", "genes": []"#,
    ));
    assert!(
        err.starts_with(
            "not a genome in JSON: unknown field `genes`, expected `generator` or `tree` at line 1"
        ),
        "{err}"
    );
    let err = load_err(&tampered("}}}}}}}", "}}}}}}"));
    assert!(
        err.starts_with("not a genome in JSON: EOF while parsing"),
        "{err}"
    );
}

#[test]
fn array_slot_mistakes_name_the_slot_and_its_length() {
    let city = |lots: &str| {
        Genome::<City>::from_json(&format!(
            r#"{{"generator": "City", "tree": {{"node": "Start", "children": {{"lots": {lots}}}}}}}"#
        ))
        .map_err(|e| error_chain(&e))
        .unwrap_err()
    };
    assert_eq!(
        city(&format!("[{}]", vec!["null"; 101].join(", "))),
        "at `Start`: slot `lots` of `Start` is an array of 100, but 101 entries are given"
    );
    assert_eq!(
        city(r#"{"node": "Lot"}"#),
        "at `Start`: slot `lots` of `Start` is an array of 100: give a list of up to 100 nodes \
         or nulls, not `{\"node\":\"Lot\"}`"
    );
    assert_eq!(
        city(
            r#"[null, {"node": "Lot", "children": {"building": {"node": "Roof", "params": {"pitch": 0.5}}}}]"#
        ),
        "at `Start > lots[1]: Lot > building`: slot `building` of `Lot` holds `Building` nodes, \
         not `Roof`"
    );
    assert_eq!(
        city(r#"[null, null, {"node": "Building"}]"#),
        "at `Start > lots[2]`: slot `lots` of `Start` holds `Lot` nodes, not `Building`"
    );
    assert_eq!(
        city(r#"[null, null, true]"#),
        "at `Start > lots[2]`: a node is an object with its type's name in `node` and, when it \
         has any, its `params` and `children`; found `true`"
    );
    assert_eq!(
        city(r#"[{"node": "Lot", "children": {"building": {"node": "Building", "params": {}}}}]"#),
        "at `Start > lots[0]: Lot > building: Building`: parameter `footprint` (Vec2) is missing"
    );
}

#[test]
fn mistakes_are_found_in_pre_order() {
    // Both the body's next and its wing are wrong: the next, at link 0, is reported, even
    // though the wing comes first in the text.
    let json = r#"{"generator": "Spaceship", "tree": {"node": "Start", "children": {"body":
        {"node": "Body", "params": {"size": [1, 1, 1]}, "children": {
            "wing": {"node": "Wing"},
            "next": {"node": "Body", "params": {"size": [9, 1, 1]}}}}}}}"#;
    assert_eq!(
        load_err(json),
        "at `Start > body: Body > next: Body`: parameter `size`: [9.0, 1.0, 1.0] is outside [[0.6, \
         0.6, 0.6], [1.5, 1.5, 1.5]]"
    );
}

/// A spaceship of `bodies` hull boxes in a row: a tree `bodies + 1` deep.
fn hull(bodies: usize) -> Genome<Spaceship> {
    let mut g = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let mut at = g
        .attach(
            0,
            "body",
            Body {
                size: glam::Vec3::ONE,
            },
        )
        .unwrap();
    for _ in 1..bodies {
        at = g
            .attach(
                at,
                "next",
                Body {
                    size: glam::Vec3::ONE,
                },
            )
            .unwrap();
    }
    g
}

#[test]
fn trees_deeper_than_json_is_read_are_refused_with_the_reason() {
    let deepest = hull(61);
    assert_eq!(
        Genome::from_json(&deepest.to_nested_json()).unwrap(),
        deepest
    );
    let err = Genome::<Spaceship>::from_json(&hull(62).to_nested_json()).unwrap_err();
    assert!(
        matches!(err, JsonError::NestedTooDeep { limit: 128, .. }),
        "{err}"
    );
    assert!(
        err.to_string()
            .starts_with("the nested form nests deeper than the 128 levels JSON is read to (line "),
        "{err}"
    );
    assert!(
        err.to_string()
            .ends_with("a tree this deep is kept in the packed form")
    );
    // The packed form holds it.
    let deep = hull(62);
    assert_eq!(Genome::from_json(&deep.to_json()).unwrap(), deep);
    // In a set too.
    let set = GenomeSet::new(vec![hull(2), hull(62)]);
    let err = GenomeSet::<Spaceship>::from_json(&set.to_nested_json()).unwrap_err();
    assert!(matches!(err, JsonError::NestedTooDeep { .. }), "{err}");
}

#[test]
fn both_forms_are_read_from_text_and_files() {
    let g = ship();
    let packed = g.to_json();
    let nested = g.to_nested_json();
    assert_ne!(packed, nested);
    assert_eq!(Genome::<Spaceship>::from_json(&packed).unwrap(), g);
    // `ship` grew out of pre-order: the nested form gives the same tree in pre-order.
    let from_nested = Genome::<Spaceship>::from_json(&nested).unwrap();
    assert_eq!(from_nested.words(), preorder(&g));
    assert_ne!(from_nested, g);
    assert_eq!(derived(&from_nested), derived(&g));

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ship.json");
    std::fs::write(&path, &nested).unwrap();
    assert_eq!(Genome::<Spaceship>::load_json(&path).unwrap(), from_nested);
    std::fs::write(&path, nested.replace("0.83", "1.83")).unwrap();
    assert_eq!(
        Genome::<Spaceship>::load_json(&path)
            .map_err(|e| error_chain(&e))
            .unwrap_err(),
        format!(
            "{}: at `Start > body: Body`: parameter `size`: [1.83, 1.2, 0.7] is outside [[0.6, \
             0.6, 0.6], [1.5, 1.5, 1.5]]",
            path.display()
        )
    );

    let set = GenomeSet::new(vec![small(), g.clone()]);
    let set_path = dir.path().join("set.json");
    std::fs::write(&set_path, set.to_nested_json()).unwrap();
    let back = GenomeSet::<Spaceship>::load(&set_path).unwrap();
    assert_eq!(back.genomes, vec![small(), from_nested.clone()]);
    std::fs::write(&set_path, set.to_json()).unwrap();
    assert_eq!(GenomeSet::<Spaceship>::load(&set_path).unwrap(), set);

    // Errors in a set name the genome, then the node.
    let bad = set.to_nested_json().replacen("0.83", "1.83", 2);
    let bad = bad.replacen("1.83", "0.83", 1);
    assert_eq!(
        GenomeSet::<Spaceship>::from_json(&bad)
            .map_err(|e| error_chain(&e))
            .unwrap_err(),
        "genome 1 of the set: at `Start > body: Body`: parameter `size`: [1.83, 1.2, 0.7] is \
         outside [[0.6, 0.6, 0.6], [1.5, 1.5, 1.5]]"
    );
    // A set is in one form: a packed genome among nested ones is refused.
    let mixed = r#"{"generator": "Spaceship", "genomes": [{"tree": {"node": "Start"}},
        {"genes": [{"node": "Start", "parent": 0, "links": [0], "params": {}}]}]}"#;
    let err = GenomeSet::<Spaceship>::from_json(mixed)
        .map_err(|e| error_chain(&e))
        .unwrap_err();
    assert!(
        err.contains("unknown field `genes`, expected `tree`"),
        "{err}"
    );
    // The other grammar's sets are refused in either form.
    assert_eq!(
        GenomeSet::<City>::from_json(&set.to_nested_json())
            .map_err(|e| error_chain(&e))
            .unwrap_err(),
        "the genome is of generator `spaceship`, but is being read as `city` (also written `City`)"
    );
}
