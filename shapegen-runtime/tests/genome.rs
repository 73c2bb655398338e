//! Building genomes by hand, validating them, printing them and their JSON form.

mod support {
    pub mod city_expanded;
    pub mod known;
    pub mod spaceship_expanded;
}

use glam::Vec3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::error_chain;
use shapegen_runtime::genome::{GeneAt, Genome, GenomeError, GenomeSet, JsonError, Limits};
use shapegen_runtime::ops::Operators;
use support::city_expanded::{self as city, City};
use support::known::{building, ship, small, v3};
use support::spaceship_expanded::{Body, Spaceship, Start, Top, TopNext};

#[test]
fn attach_appends_genes_with_relative_offsets() {
    let g = ship();
    assert_eq!(g.len(), 7);
    assert_eq!(g.words().len(), 3 + 8 + 8 + 7 + 7 + 6 + 6);
    let w = g.words();
    assert_eq!(&w[0..3], &[0, 0, 3]);
    // Body @3: kind 1, parent -3, links next +8, wing +16, top 0.
    assert_eq!(&w[3..8], &[1, (-3i32) as u32, 8, 16, 0]);
    assert_eq!(f32::from_bits(w[8]), 0.83);
    // Top @33 hangs from Body @11 by its third link.
    assert_eq!(w[11 + 4], 22);
    assert_eq!(w[33 + 1] as i32, -22);
    g.validate().unwrap();
    assert_eq!(g.depth(), 5);
    let mut out = Vec::new();
    g.derive_into(&mut out);
    // Two bodies, two mirrored pairs of wing boxes (Wing and WingNext), two tower boxes.
    assert_eq!(out.len(), 2 + 2 * 2 + 2);
}

#[test]
fn attach_reports_each_mistake_and_leaves_the_genome_alone() {
    let mut g = ship();
    let before = g.clone();
    let body = Body {
        size: v3(1.0, 1.0, 1.0),
    };
    let err = g.attach(3, "nose", body).unwrap_err();
    assert_eq!(
        err.to_string(),
        "`Body` has no child slot `nose`; its slots are: `next`, `wing`, `top`"
    );
    let err = g.attach(3, "next", body).unwrap_err();
    assert!(
        matches!(err, GenomeError::Occupied { child: 11, .. }),
        "{err}"
    );
    assert_eq!(
        err.to_string(),
        "gene 1 (`Body` @3): slot `next` already holds the gene @11"
    );
    let err = g.attach(11, "wing", body).unwrap_err();
    assert_eq!(
        err.to_string(),
        "slot `wing` of `Body` holds `Wing` genes, but the parameters given are of `Body`"
    );
    let err = g.attach(4, "next", body).unwrap_err();
    assert!(matches!(err, GenomeError::NotAGene { pos: 4, .. }), "{err}");
    let err = g
        .attach(
            11,
            "next",
            Body {
                size: v3(2.0, 1.0, 1.0),
            },
        )
        .unwrap_err();
    assert!(
        matches!(err, GenomeError::Param { param: "size", .. }),
        "{err}"
    );
    assert!(err.to_string().contains("gene 7 (`Body` @45)"), "{err}");
    assert!(err.to_string().contains("outside"), "{err}");
    let err = g.attach_at(11, "next", 1, body).unwrap_err();
    assert!(
        matches!(
            err,
            GenomeError::SlotIndex {
                index: 1,
                count: 1,
                ..
            }
        ),
        "{err}"
    );
    // Parameter structs of another grammar are refused.
    let err = g.attach(11, "next", city::Roof { pitch: 0.5 }).unwrap_err();
    assert!(matches!(err, GenomeError::ForeignParams { .. }), "{err}");
    assert_eq!(g, before);
    g.validate().unwrap();
    assert_eq!(g.attach_at(11, "next", 0, body), Ok(45));
}

#[test]
fn with_root_wants_the_axiom() {
    let err = Genome::<Spaceship>::with_root(Body {
        size: v3(1.0, 1.0, 1.0),
    })
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "the root of `Spaceship` holds `Start` genes, but the parameters given are of `Body`"
    );
}

#[test]
fn array_slots_take_an_index() {
    let mut g = Genome::<City>::with_root(city::Start {}).unwrap();
    let err = g.attach(0, "lots", city::Lot {}).unwrap_err();
    assert_eq!(
        err.to_string(),
        "slot `lots` of `Start` is an array of 100; name the index with `attach_at`"
    );
    let lot = g.attach_at(0, "lots", 42, city::Lot {}).unwrap();
    assert_eq!(lot, 102);
    assert_eq!(g.words()[2 + 42], 102);
    let err = g.attach_at(0, "lots", 100, city::Lot {}).unwrap_err();
    assert!(matches!(
        err,
        GenomeError::SlotIndex {
            index: 100,
            count: 100,
            ..
        }
    ));
    let b = g.attach(lot, "building", building(5.0)).unwrap();
    g.attach(b, "roof", city::Roof { pitch: 0.3 }).unwrap();
    let err = g.attach_at(0, "lots", 42, city::Lot {}).unwrap_err();
    assert_eq!(
        err.to_string(),
        "gene 0 (`Start` @0): slot `lots[42]` already holds the gene @102"
    );
    let roof = g.words()[b as usize + 2] + b;
    let err = g
        .attach(roof, "spire", city::Roof { pitch: 0.0 })
        .unwrap_err();
    assert!(err.to_string().contains("`pitch`"), "{err}");
    g.validate().unwrap();
    let mut out = Vec::new();
    g.derive_into(&mut out);
    assert_eq!(out.len(), 2);
}

#[test]
fn display_is_an_indented_tree() {
    let g = ship();
    assert_eq!(
        g.to_string(),
        "\
Start @0
  body: Body @3 size=(0.83, 1.20, 0.70)
    next: Body @11 size=(1.00, 1.00, 1.00)
      top: Top @33 size=(0.50, 0.15, 0.50)
        next: TopNext @39 size=(1.00, 1.00, 1.00)
    wing: Wing @19 size=(0.50, 0.30, 0.70) shift=0.10
      next: WingNext @26 size=(0.90, 0.95, 1.00) shift=-0.25
"
    );
    let dbg = format!("{:?}", small());
    assert_eq!(
        dbg,
        "\
Genome<Spaceship>: 3 genes, 18 words
Start @0
  body: Body @3 size=(0.83, 1.2, 0.7)
    wing: Wing @11 size=(0.5, 0.3, 0.7) shift=0.1
"
    );
}

#[test]
fn display_shows_angles_in_their_unit_and_array_indices() {
    let mut g = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = g.attach_at(0, "lots", 7, city::Lot {}).unwrap();
    let b = g.attach(lot, "building", building(4.5)).unwrap();
    g.attach(b, "roof", city::Roof { pitch: 0.5 }).unwrap();
    assert_eq!(
        g.to_string(),
        "\
Start @0
  lots[7]: Lot @102
    building: Building @105 footprint=(1.00, 1.50) height=4.50 rotation=30.00° style=2 floors=-1 lit=true block=3
      roof: Roof @116 pitch=0.50 rad
"
    );
}

#[test]
fn json_is_readable_one_gene_a_line() {
    let json = small().to_json();
    assert_eq!(
        json,
        r#"{
  "generator": "spaceship",
  "genes": [
    {"node": "Start", "parent": 0, "links": [3], "params": {}},
    {"node": "Body", "parent": -3, "links": [0, 8, 0], "params": {"size": [0.83, 1.2, 0.7]}},
    {"node": "Wing", "parent": -8, "links": [0], "params": {"size": [0.5, 0.3, 0.7], "shift": 0.1}}
  ]
}
"#
    );
    assert_eq!(Genome::<Spaceship>::from_json(&json).unwrap(), small());
    // The compact serde form reads back too, through `Deserialize`.
    let compact = serde_json::to_string(&small()).unwrap();
    let back: Genome<Spaceship> = serde_json::from_str(&compact).unwrap();
    assert_eq!(back, small());
}

#[test]
fn json_writes_every_parameter_type() {
    let mut g = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = g.attach_at(0, "lots", 1, city::Lot {}).unwrap();
    g.attach(lot, "building", building(4.5)).unwrap();
    let json = g.to_json();
    let line = json.lines().nth(5).unwrap();
    assert_eq!(
        line,
        r#"    {"node": "Building", "parent": -3, "links": [0], "params": {"footprint": [1.0, 1.5], "height": 4.5, "rotation": 0.5235988, "style": 2, "floors": -1, "lit": true, "block": 3}}"#
    );
    assert_eq!(Genome::<City>::from_json(&json).unwrap(), g);
}

#[test]
fn a_file_names_its_generator_by_key_or_by_grammar_name() {
    // Written with the key, the name the tool knows the generator by; the grammar's own
    // name reads as well, in either form; another spelling is refused with both.
    assert!(small().to_json().contains(r#""generator": "spaceship""#));
    for json in [small().to_json(), small().to_nested_json()] {
        let grammar = json.replacen(r#""spaceship""#, r#""Spaceship""#, 1);
        assert_eq!(Genome::<Spaceship>::from_json(&grammar).unwrap(), small());
        let other = json.replacen(r#""spaceship""#, r#""SpaceShip""#, 1);
        assert_eq!(
            error_chain(&Genome::<Spaceship>::from_json(&other).unwrap_err()),
            "the genome is of generator `SpaceShip`, but is being read as `spaceship` (also \
             written `Spaceship`)"
        );
    }
}

/// `small()`'s JSON with `from` replaced by `to`.
fn tampered(from: &str, to: &str) -> String {
    let json = small().to_json();
    assert!(json.contains(from), "{from} not in {json}");
    json.replacen(from, to, 1)
}

fn load_err(json: &str) -> String {
    Genome::<Spaceship>::from_json(json)
        .map_err(|e| error_chain(&e))
        .unwrap_err()
}

#[test]
fn json_load_names_what_is_wrong() {
    let cases = [
        (
            tampered(r#""generator": "spaceship""#, r#""generator": "city""#),
            "the genome is of generator `city`, but is being read as `spaceship` (also written `Spaceship`)",
        ),
        (
            tampered(r#""node": "Wing""#, r#""node": "Wong""#),
            "gene 2: `Wong` is not a node of `Spaceship`; its nodes are: `Start`, `Body`, `Top`, \
             `TopNext`, `Wing`, `WingNext`",
        ),
        (
            tampered(r#""links": [0, 8, 0]"#, r#""links": [0, 8]"#),
            "gene 1 (`Body`): 2 links given, but `Body` has 3: `next`, `wing`, `top`",
        ),
        (
            tampered(r#", "shift": 0.1"#, ""),
            "gene 2 (`Wing`): parameter `shift` (f32) is missing",
        ),
        (
            tampered(r#""shift": 0.1"#, r#""shift": 0.1, "tilt": 3"#),
            "gene 2 (`Wing`): `tilt` is not a parameter of `Wing`; its parameters are: `size`, \
             `shift`",
        ),
        (
            tampered(r#""shift": 0.1"#, r#""shift": "left""#),
            "gene 2 (`Wing`): parameter `shift` must be a number (f32), not `\"left\"`",
        ),
        (
            tampered("[0.83, 1.2, 0.7]", "[0.83, 1.2]"),
            "gene 1 (`Body`): parameter `size` must be an array of 3 numbers (Vec3), not \
             `[0.83,1.2]`",
        ),
        (
            tampered(r#""shift": 0.1"#, r#""shift": 0.6"#),
            "invalid genome: gene 2 (`Wing` @11): parameter `shift`: 0.6 is outside [-0.5, 0.5]",
        ),
        (
            tampered(r#""parent": -8"#, r#""parent": -5"#),
            "invalid genome: gene 2 (`Wing` @11) has parent offset -5, which lands on word 6: \
             not the start of a gene",
        ),
        (
            tampered(r#""parent": -8"#, r#""parent": -11"#),
            "invalid genome: gene 1 (`Body` @3): slot `wing` links to gene 2 (`Wing` @11), whose \
             parent offset names word 0 instead; a gene is linked from its own parent only",
        ),
        (
            tampered(r#""links": [0, 8, 0]"#, r#""links": [0, 0, 0]"#),
            "invalid genome: gene 2 (`Wing` @11) names gene 1 (`Body` @3) as its parent, which \
             links to it on 0 links instead of exactly one",
        ),
        (
            tampered(r#""links": [0, 8, 0]"#, r#""links": [0, 8, 8]"#),
            "invalid genome: gene 1 (`Body` @3): slot `top` links to gene 2 (`Wing` @11), but \
             that slot holds `Top` genes",
        ),
        (
            tampered(r#""links": [0, 8, 0]"#, r#""links": [0, 9, 0]"#),
            "invalid genome: gene 1 (`Body` @3): slot `wing` has offset 9, which lands on word \
             12: not the start of a gene",
        ),
        (
            tampered(r#""links": [0, 8, 0]"#, r#""links": [-3, 8, 0]"#),
            "invalid genome: gene 1 (`Body` @3): slot `next` has offset -3; a child lies after \
             its parent, so a link's offset is positive (or 0 when the child is absent)",
        ),
        (
            tampered(r#""parent": -3"#, r#""parent": 0"#),
            "invalid genome: gene 1 (`Body` @3) has parent offset 0; every gene but the root \
             lies after its parent, so its parent offset must be negative",
        ),
        (
            tampered(
                r#"{"node": "Start", "parent": 0"#,
                r#"{"node": "Start", "parent": 2"#,
            ),
            "invalid genome: the root gene has parent offset 2; the root's parent offset must \
             be 0",
        ),
        (
            r#"{"generator": "Spaceship", "genes": []}"#.to_owned(),
            "invalid genome: the genome holds no gene; it needs at least its root, of the axiom \
             `Start`",
        ),
    ];
    for (json, msg) in &cases {
        assert_eq!(&load_err(json), msg, "for {json}");
    }
    assert!(load_err("{").starts_with("not a genome in JSON: EOF while parsing"));
    let unknown_field = tampered(r#""parent": -8"#, r#""parent": -8, "depth": 3"#);
    assert!(load_err(&unknown_field).contains("unknown field `depth`"));
    // Through serde the messages are the same.
    let json = tampered(r#""shift": 0.1"#, r#""shift": 0.6"#);
    let err = serde_json::from_str::<Genome<Spaceship>>(&json)
        .map_err(|e| error_chain(&e))
        .unwrap_err();
    assert!(err.contains("parameter `shift`: 0.6 is outside"), "{err}");
}

#[test]
fn json_load_rejects_a_gene_linked_twice_and_a_wrong_root() {
    // Both bodies claim the Wing on their wing links.
    let json = r#"{"generator": "Spaceship", "genes": [
        {"node": "Start", "parent": 0, "links": [3], "params": {}},
        {"node": "Body", "parent": -3, "links": [8, 16, 0], "params": {"size": [1, 1, 1]}},
        {"node": "Body", "parent": -8, "links": [0, 8, 0], "params": {"size": [1, 1, 1]}},
        {"node": "Wing", "parent": -16, "links": [0], "params": {"size": [0.5, 0.3, 0.7], "shift": 0}}
    ]}"#;
    let err = Genome::<Spaceship>::from_json(json).unwrap_err();
    let JsonError::Invalid(inner) = &err else {
        panic!("{err}")
    };
    assert!(
        matches!(
            inner,
            GenomeError::ForeignChild {
                child_parent: 3,
                ..
            }
        ),
        "{inner}"
    );
    assert_eq!(
        inner.to_string(),
        "gene 2 (`Body` @11): slot `wing` links to gene 3 (`Wing` @19), whose parent offset \
         names word 3 instead; a gene is linked from its own parent only"
    );
    let json = r#"{"generator": "Spaceship", "genes": [
        {"node": "Body", "parent": 0, "links": [0, 0, 0], "params": {"size": [1, 1, 1]}}
    ]}"#;
    assert_eq!(
        load_err(json),
        "invalid genome: the root gene is `Body`, but the axiom of `Spaceship` is `Start`"
    );
}

#[test]
fn json_integer_parameters_are_checked() {
    let mut g = Genome::<City>::with_root(city::Start {}).unwrap();
    let lot = g.attach_at(0, "lots", 1, city::Lot {}).unwrap();
    g.attach(lot, "building", building(4.5)).unwrap();
    let json = g.to_json();
    let load = |from: &str, to: &str| {
        Genome::<City>::from_json(&json.replacen(from, to, 1))
            .map_err(|e| error_chain(&e))
            .unwrap_err()
    };
    assert_eq!(
        load(r#""floors": -1"#, r#""floors": -1.5"#),
        "gene 2 (`Building`): parameter `floors` must be an integer (i32), not `-1.5`"
    );
    assert_eq!(
        load(r#""block": 3"#, r#""block": -3"#),
        "gene 2 (`Building`): parameter `block` must be a non-negative integer (u32), not `-3`"
    );
    assert_eq!(
        load(r#""lit": true"#, r#""lit": 1"#),
        "gene 2 (`Building`): parameter `lit` must be true or false (bool), not `1`"
    );
    assert_eq!(
        load(r#""style": 2"#, r#""style": 1"#),
        "invalid genome: gene 2 (`Building` @105): parameter `style`: 1 is not a choice with \
         positive weight among 4 choices"
    );
    assert_eq!(
        load(r#""floors": -1"#, r#""floors": 6"#),
        "invalid genome: gene 2 (`Building` @105): parameter `floors`: 6 is outside -2..=5"
    );
}

#[test]
fn json_files_and_sets() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("genome.json");
    ship().save_json(&path).unwrap();
    assert_eq!(Genome::<Spaceship>::load_json(&path).unwrap(), ship());

    let missing = dir.path().join("missing.json");
    let err = Genome::<Spaceship>::load_json(&missing)
        .map_err(|e| error_chain(&e))
        .unwrap_err();
    assert!(
        err.starts_with(&format!("{}: ", missing.display())),
        "{err}"
    );

    std::fs::write(&path, small().to_json().replace("0.83", "1.83")).unwrap();
    let err = Genome::<Spaceship>::load_json(&path)
        .map_err(|e| error_chain(&e))
        .unwrap_err();
    assert_eq!(
        err,
        format!(
            "{}: invalid genome: gene 1 (`Body` @3): parameter `size`: [1.83, 1.2, 0.7] is \
             outside [[0.6, 0.6, 0.6], [1.5, 1.5, 1.5]]",
            path.display()
        )
    );

    let mut ops = Operators::<Spaceship>::new(Limits::new(1, 60, 12).unwrap()).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let set = GenomeSet::new((0..5).map(|_| ops.random(20, &mut rng)).collect());
    let set_path = dir.path().join("genomes.json");
    set.save(&set_path).unwrap();
    let back = GenomeSet::<Spaceship>::load(&set_path).unwrap();
    assert_eq!(back, set);
    let text = std::fs::read_to_string(&set_path).unwrap();
    assert!(text.starts_with("{\n  \"generator\": \"spaceship\",\n  \"genomes\": [\n    {\n      \"genes\": [\n        {\"node\": \"Start\", "), "{text}");
    // An error names the genome of the set.
    let third = text.match_indices(r#""links": [3]"#).nth(2).unwrap().0;
    let bad = format!(
        "{}{}",
        &text[..third],
        text[third..].replacen("[3]", "[4]", 1)
    );
    let err = GenomeSet::<Spaceship>::from_json(&bad)
        .map_err(|e| error_chain(&e))
        .unwrap_err();
    assert_eq!(
        err,
        "genome 2 of the set: invalid genome: gene 0 (`Start` @0): slot `body` has offset 4, \
         which lands on word 4: not the start of a gene"
    );
    let err = GenomeSet::<City>::from_json(&text)
        .map_err(|e| error_chain(&e))
        .unwrap_err();
    assert_eq!(
        err,
        "the genome is of generator `spaceship`, but is being read as `city` (also written `City`)"
    );
}

#[test]
fn validate_limits_reports_length_and_depth() {
    let g = ship();
    assert!(g.validate_limits(&Limits::new(1, 7, 5).unwrap()).is_ok());
    assert_eq!(
        g.validate_limits(&Limits::new(8, 10, 5).unwrap()),
        Err(GenomeError::TooShort { len: 7, min_len: 8 })
    );
    assert_eq!(
        g.validate_limits(&Limits::new(1, 6, 5).unwrap()),
        Err(GenomeError::TooLong { len: 7, max_len: 6 })
    );
    assert_eq!(
        g.validate_limits(&Limits::new(1, 7, 3).unwrap()),
        Err(GenomeError::DeeperThanLimit {
            at: GeneAt {
                index: 4,
                pos: 26,
                node: "WingNext"
            },
            depth: 4,
            max_depth: 3
        })
    );
}

#[test]
fn genome_depth_is_capped() {
    // A chain of TopNext genes may not pass DEPTH_CAP.
    let mut g = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let mut pos = g.attach(0, "body", Body { size: Vec3::ONE }).unwrap();
    pos = g
        .attach(
            pos,
            "top",
            Top {
                size: v3(0.5, 0.15, 0.5),
            },
        )
        .unwrap();
    for _ in 3..shapegen_runtime::genome::DEPTH_CAP {
        pos = g.attach(pos, "next", TopNext { size: Vec3::ONE }).unwrap();
    }
    assert_eq!(g.depth(), shapegen_runtime::genome::DEPTH_CAP);
    let err = g
        .attach(pos, "next", TopNext { size: Vec3::ONE })
        .unwrap_err();
    assert!(
        matches!(
            err,
            GenomeError::TooDeep {
                depth: 1025,
                cap: 1024,
                ..
            }
        ),
        "{err}"
    );
    g.validate().unwrap();
}
