//! Priors learned across tasks: the estimator's laws, the file's
//! errors, and learning with a uniform priors file equal to learning
//! without one.

use proptest::prelude::*;
use rccpack::infer::{learn, LearnParams};
use rccpack::priors::{combine, Count, PriorParams, Priors, PriorsError, TaskCounts};
use rccpack::scene::scenes_from_json;
use std::collections::BTreeMap;

const KINDS: &[&str] = &[
    "{A}_dr_{d}_{B}/fixed/s",
    "{A}_dr_{d}_{B}/movable/n",
    "{A}_ec_{d}_{B}/own/w",
    "{A}_touches_{B}/movable",
    "{A}_inside_{B}/fixed",
    "{A}_corner/any",
    "{A}_row/self",
];

fn kind(i: usize) -> String {
    // `own` is not a role name: use `self` for the self-target kinds.
    KINDS[i % KINDS.len()].replace("/own/", "/self/")
}

/// A task: per kind index, (candidates, kept ≤ candidates).
fn task_strategy() -> impl Strategy<Value = TaskCounts> {
    (
        any::<u64>(),
        prop::collection::btree_map(0..KINDS.len(), (1u64..6, 0u64..6), 0..5),
    )
        .prop_map(|(hash, m)| TaskCounts {
            hash,
            kinds: m
                .into_iter()
                .map(|(k, (c, kept))| {
                    (
                        kind(k),
                        Count {
                            candidates: c,
                            kept: kept.min(c),
                            confirmed: 0,
                        },
                    )
                })
                .collect(),
        })
}

fn params(rule_out_after: u64) -> PriorParams {
    PriorParams {
        rule_out_after,
        ..PriorParams::default()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn priors_are_inside_the_unit_interval_and_rule_out_follows_the_threshold(
        tasks in prop::collection::vec(task_strategy(), 0..12),
        after in 0u64..6,
    ) {
        let p = combine(&tasks, &params(after));
        for e in &p.kinds {
            prop_assert!(e.prior > 0.0 && e.prior < 1.0, "{} has prior {}", e.kind, e.prior);
            if e.kept > 0 {
                prop_assert!(!e.ruled_out, "{} was kept and is ruled out", e.kind);
            }
            if e.ruled_out {
                // Some node on its path is past the threshold and never kept.
                let mut k = Some(e.kind.clone());
                let mut found = false;
                while let Some(key) = k {
                    let n = p.kinds.iter().find(|x| x.kind == key).unwrap();
                    found |= after > 0 && n.tasks >= after && n.kept == 0;
                    k = rccpack::priors::kind::parent_key(&key);
                }
                prop_assert!(found, "{} ruled out below the threshold", e.kind);
            }
        }
        // The file round-trips byte for byte.
        let text = p.to_json();
        let back = Priors::from_json(&text).unwrap();
        prop_assert_eq!(back.to_json(), text);
    }

    #[test]
    fn the_library_order_changes_nothing(
        tasks in prop::collection::vec(task_strategy(), 0..10),
        seed in any::<u64>(),
    ) {
        let mut shuffled = tasks.clone();
        // A deterministic permutation from the seed.
        let n = shuffled.len();
        for i in (1..n).rev() {
            let j = (seed.rotate_left(i as u32) % (i as u64 + 1)) as usize;
            shuffled.swap(i, j);
        }
        prop_assert_eq!(combine(&tasks, &params(3)).to_json(), combine(&shuffled, &params(3)).to_json());
    }

    #[test]
    fn a_task_keeping_every_candidate_of_a_kind_raises_its_prior(
        tasks in prop::collection::vec(task_strategy(), 0..10),
        k in 0..KINDS.len(),
        c in 1u64..5,
    ) {
        let key = kind(k);
        let before = combine(&tasks, &params(0));
        let mut more = tasks.clone();
        more.push(TaskCounts {
            hash: 7,
            kinds: BTreeMap::from([(key.clone(), Count { candidates: c, kept: c, confirmed: 0 })]),
        });
        let after = combine(&more, &params(0));
        let prior = |p: &Priors| {
            let kind = p.kinds.iter().find(|e| e.kind == key);
            kind.map(|e| e.prior)
        };
        let a = prior(&after).unwrap();
        // Absent before: it had its nearest ancestor's prior.
        let b = prior(&before).unwrap_or_else(|| {
            let mut k = rccpack::priors::kind::parent_key(&key);
            loop {
                let key = k.unwrap();
                if let Some(e) = before.kinds.iter().find(|e| e.kind == key) {
                    break e.prior;
                }
                k = rccpack::priors::kind::parent_key(&key);
            }
        });
        prop_assert!(a > b, "{key}: {b} -> {a}");
    }
}

#[test]
fn an_absent_kind_gets_its_parents_prior() {
    let tasks = vec![TaskCounts {
        hash: 1,
        kinds: BTreeMap::from([(
            "{A}_dr_{d}_{B}/fixed/s".to_string(),
            Count {
                candidates: 3,
                kept: 3,
                confirmed: 0,
            },
        )]),
    }];
    let p = combine(&tasks, &PriorParams::default());
    let parent = p
        .kinds
        .iter()
        .find(|e| e.kind == "{A}_dr_{d}_{B}/fixed")
        .unwrap();
    let absent = rccpack::priors::Kind {
        template: "{A}_dr_{d}_{B}",
        role: rccpack::priors::Role::Fixed,
        dir: Some(rccpack::relations::Dir::N),
    };
    assert_eq!(p.lookup(&absent).prior, parent.prior);
    let other = rccpack::priors::Kind {
        template: "{A}_corner",
        role: rccpack::priors::Role::Any,
        dir: None,
    };
    assert_eq!(p.lookup(&other).kind, "*");
    assert_eq!(p.lookup(&other).prior, p.root().prior);
}

const DEMOS: &str = r#"[
 {"space":{"width":60,"height":60},"objects":[
  {"class":"B","x":0,"y":40,"width":10,"height":10},
  {"class":"B","x":20,"y":40,"width":10,"height":10},
  {"class":"R","x":0,"y":0,"width":10,"height":10},
  {"class":"W","x":0,"y":55,"width":60,"height":5,"fixed":true,"id":"wall"}]},
 {"space":{"width":60,"height":60},"objects":[
  {"class":"B","x":30,"y":45,"width":10,"height":10},
  {"class":"B","x":10,"y":30,"width":10,"height":10},
  {"class":"R","x":40,"y":5,"width":10,"height":10},
  {"class":"W","x":0,"y":55,"width":60,"height":5,"fixed":true,"id":"wall"}]}
]"#;

#[test]
fn a_uniform_priors_file_learns_what_no_priors_file_learns() {
    let demos = scenes_from_json(DEMOS).unwrap();
    let params = LearnParams {
        samples: 200,
        ..LearnParams::default()
    };
    let none = learn(&demos, None, &params).unwrap();
    // An empty library: every kind gets the root's prior 1/2.
    let empty = combine(&[], &PriorParams::default());
    assert_eq!(empty.root().prior, 0.5);
    // A library whose every node keeps half its candidates: 1/2 too.
    let half = combine(
        &[TaskCounts {
            hash: 3,
            kinds: BTreeMap::from([(
                "{A}_dr_{d}_{B}/fixed/s".to_string(),
                Count {
                    candidates: 4,
                    kept: 2,
                    confirmed: 0,
                },
            )]),
        }],
        &PriorParams::default(),
    );
    for uniform in [empty, half] {
        let file = Priors::from_json(&uniform.to_json()).unwrap();
        let with = learn_with_priors(&demos, None, &params, &file).unwrap();
        assert_eq!(with.to_rcc(), none.to_rcc());
        assert!(with
            .statements
            .iter()
            .all(|s| s.prior.as_ref().unwrap().prior == 0.5));
        assert_eq!(with.order, none.order);
    }
    // A real prior changes the header and the posteriors.
    let strong = combine(
        &[TaskCounts {
            hash: 5,
            kinds: BTreeMap::from([(
                "{A}_dr_{d}_{B}/fixed/s".to_string(),
                Count {
                    candidates: 4,
                    kept: 0,
                    confirmed: 0,
                },
            )]),
        }],
        &PriorParams::default(),
    );
    let with = learn_with_priors(&demos, None, &params, &strong).unwrap();
    assert_ne!(with.to_rcc(), none.to_rcc());
    assert!(with.to_rcc().contains("# priors fnv1a64:"));
}

#[test]
fn a_ruled_out_kind_is_left_out_of_the_statements() {
    let demos = scenes_from_json(DEMOS).unwrap();
    let params = LearnParams {
        samples: 100,
        ..LearnParams::default()
    };
    let never = TaskCounts {
        hash: 0,
        kinds: BTreeMap::from([(
            "{A}_dr_{d}_{B}/movable".to_string(),
            Count {
                candidates: 1,
                kept: 0,
                confirmed: 0,
            },
        )]),
    };
    let p = combine(&vec![never; 3], &params_after(3));
    let with = learn_with_priors(&demos, None, &params, &p).unwrap();
    let used = with.priors.as_ref().unwrap();
    assert!(!used.ruled_out.is_empty());
    assert!(used
        .ruled_out
        .iter()
        .all(|r| r.kind.starts_with("{A}_dr_{d}_{B}/")));
    assert!(with
        .statements
        .iter()
        .all(|s| !used.ruled_out.iter().any(|r| r.name == s.name)));
    // Given statements keep the uniform prior and are never ruled out.
    let given = rccpack::parse_rules("rule x: DR_N(B, R)\n").unwrap();
    let with = learn_with_priors(&demos, Some(&given), &params, &p).unwrap();
    assert_eq!(with.statements.len(), 1);
    assert_eq!(with.statements[0].prior.as_ref().unwrap().from, None);
}

fn params_after(n: u64) -> PriorParams {
    PriorParams {
        rule_out_after: n,
        ..PriorParams::default()
    }
}

fn field_of(text: &str) -> String {
    match Priors::from_json(text) {
        Err(PriorsError::Field { field, .. }) => field,
        Err(e) => panic!("not a field error: {e}"),
        Ok(_) => panic!("accepted"),
    }
}

#[test]
fn a_bad_priors_file_names_the_field() {
    let p = combine(
        &[TaskCounts {
            hash: 9,
            kinds: BTreeMap::from([(
                "{A}_touches_{B}/movable".to_string(),
                Count {
                    candidates: 3,
                    kept: 1,
                    confirmed: 0,
                },
            )]),
        }],
        &PriorParams::default(),
    );
    let good = p.to_json();
    assert!(Priors::from_json(&good).is_ok());
    let version = good.replace("rccpack-priors/1", "rccpack-priors/9");
    assert_eq!(field_of(&version), "version");
    let unknown = good.replace("{A}_touches_{B}/movable", "{A}_hugs_{B}/movable");
    assert_eq!(field_of(&unknown), "kinds[2].kind");
    let role = good.replace("{A}_touches_{B}/movable", "{A}_touches_{B}/robot");
    assert_eq!(field_of(&role), "kinds[2].kind");
    let v: serde_json::Value = serde_json::from_str(&good).unwrap();
    let mut out = v.clone();
    out["kinds"][1]["prior"] = serde_json::json!(1.5);
    assert_eq!(field_of(&out.to_string()), "kinds[1].prior");
    let mut edited = v.clone();
    edited["kinds"][1]["prior"] = serde_json::json!(0.9);
    assert_eq!(field_of(&edited.to_string()), "kinds[1].prior");
    let mut counts = v.clone();
    counts["kinds"][1]["kept"] = serde_json::json!(0);
    assert_eq!(field_of(&counts.to_string()), "hash");
    let mut hash = v.clone();
    hash["hash"] = serde_json::json!("fnv1a64:0000000000000000");
    let msg = Priors::from_json(&hash.to_string())
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("`hash`") && msg.contains("fnv1a64:0000000000000000"),
        "{msg}"
    );
    let extra = good.replacen("\"version\"", "\"colour\": 1, \"version\"", 1);
    let msg = Priors::from_json(&extra).unwrap_err().to_string();
    assert!(msg.contains("colour"), "{msg}");
}

#[test]
fn cli_priors_same_bytes_on_one_and_two_threads_and_learn_takes_them() {
    let dir = crate::support::scratch("priors-cli");
    // Two task folders: the bundled examples with a learned.rcc each.
    let mut tasks = Vec::new();
    for (name, rules) in [("box-packing", "pilot.rcc"), ("shelf", "intended.rcc")] {
        let t = dir.join(name);
        std::fs::create_dir_all(&t).unwrap();
        let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples")
            .join(name);
        std::fs::copy(src.join("demos.json"), t.join("demos.json")).unwrap();
        std::fs::copy(src.join(rules), t.join("learned.rcc")).unwrap();
        tasks.push(t);
    }
    let run = |threads: &str, out: &str| {
        let o = crate::support::command()
            .arg("priors")
            .args(&tasks)
            .args(["--threads", threads, "-o"])
            .arg(dir.join(out))
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(dir.join(out)).unwrap()
    };
    let one = run("1", "p1.json");
    let two = run("2", "p2.json");
    assert_eq!(one, two);
    let p = Priors::from_json(&one).unwrap();
    assert_eq!(p.tasks, 2);
    assert!(
        p.root().kept > 0,
        "the kept rules are matched to candidates"
    );
    // Reversed folder order: the same bytes.
    let o = crate::support::command()
        .arg("priors")
        .args(tasks.iter().rev())
        .output()
        .unwrap();
    assert_eq!(String::from_utf8(o.stdout).unwrap(), one);

    // A uniform priors file (an empty library's) learns the same bytes as none.
    let uniform = dir.join("uniform.json");
    std::fs::write(&uniform, combine(&[], &PriorParams::default()).to_json()).unwrap();
    let demos = tasks[1].join("demos.json");
    let learn = |extra: &[&std::ffi::OsStr]| {
        let o = crate::support::command()
            .arg("learn")
            .arg(&demos)
            .args(["--samples", "100"])
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        o.stdout
    };
    assert_eq!(
        learn(&[]),
        learn(&["--priors".as_ref(), uniform.as_os_str()])
    );
    // A bad file: exit 1, the file and the field named.
    let bad = dir.join("bad.json");
    std::fs::write(&bad, one.replace("rccpack-priors/1", "rccpack-priors/0")).unwrap();
    let o = crate::support::command()
        .arg("learn")
        .arg(&demos)
        .arg("--priors")
        .arg(&bad)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("bad.json") && err.contains("`version`"),
        "{err}"
    );
    // The report shows each statement's prior and its source.
    let report = dir.join("report.json");
    let o = crate::support::command()
        .arg("learn")
        .arg(&demos)
        .args(["--samples", "100", "--priors"])
        .arg(dir.join("p1.json"))
        .arg("--report")
        .arg(&report)
        .output()
        .unwrap();
    assert!(o.status.success());
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let s0 = &r["statements"][0]["prior"];
    assert!(
        s0["prior"].as_f64().unwrap() > 0.0 && s0["from"].is_string(),
        "{s0}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Counts carried as plain data (Python's `task_counts`, a cluster)
    /// come back equal, so they combine into the same bytes.
    #[test]
    fn task_counts_round_trip_as_plain_data(tasks in prop::collection::vec(task_strategy(), 0..6)) {
        let p = PriorParams::default();
        let texts: Vec<String> = tasks.iter().map(|t| t.to_json(&p)).collect();
        let back = rccpack::priors::counts_from_json_list(&format!("[{}]", texts.join(",")), &p).unwrap();
        prop_assert_eq!(&back, &tasks);
        for (t, text) in tasks.iter().zip(&texts) {
            prop_assert_eq!(&TaskCounts::from_json(text, &p).unwrap(), t);
        }
        prop_assert_eq!(combine(&back, &p).to_json(), combine(&tasks, &p).to_json());
    }
}

#[test]
fn bad_plain_counts_name_the_field() {
    let p = PriorParams::default();
    let t = TaskCounts {
        hash: 1,
        kinds: BTreeMap::from([(
            "{A}_corner/any".to_string(),
            Count {
                candidates: 2,
                kept: 1,
                confirmed: 0,
            },
        )]),
    };
    let good = t.to_json(&p);
    let field = |text: &str| match rccpack::priors::counts_from_json_list(text, &p) {
        Err(PriorsError::Counts { field, .. } | PriorsError::CountsJson { field, .. }) => field,
        other => panic!("{other:?}"),
    };
    let second = PriorParams {
        templates: rccpack::infer::Templates::Second,
        ..p
    };
    assert_eq!(
        field(&format!("[{good},{}]", t.to_json(&second))),
        "counts[1].templates"
    );
    let edge = PriorParams {
        contact: rccpack::relations::Contact::Edge,
        ..p
    };
    assert_eq!(
        field(&format!("[{}]", t.to_json(&edge))),
        "counts[0].contact"
    );
    let bad = good.replace("\"kept\":1", "\"kept\":3");
    assert_eq!(
        field(&format!("[{bad}]")),
        "counts[0].kinds.{A}_corner/any.kept"
    );
    let bad = good.replace("\"candidates\":2", "\"candidates\":0");
    assert_eq!(
        field(&format!("[{bad}]")),
        "counts[0].kinds.{A}_corner/any.candidates"
    );
    let bad = good.replace("{A}_corner/any", "{A}_corner");
    assert_eq!(field(&format!("[{bad}]")), "counts[0].kinds.{A}_corner");
    let bad = good.replace("\"kept\":1", "\"kept\":-1");
    assert_eq!(
        field(&format!("[{bad}]")),
        "counts[0].kinds.{A}_corner/any.kept"
    );
    let bad = good.replace("task-counts/1", "task-counts/2");
    assert_eq!(field(&format!("[{bad}]")), "counts[0].version");
    assert_eq!(field(&good), "counts");
    // One task alone: the field without the list's index.
    match TaskCounts::from_json(&t.to_json(&second), &p) {
        Err(PriorsError::Counts { field, message }) => {
            assert_eq!(field, "templates");
            assert!(message.contains("second"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// Learning with priors ([`rccpack::infer::learn_with`] with
/// `LearnOptions::priors`).
fn learn_with_priors(
    demos: &[rccpack::scene::Scene],
    statements: Option<&rccpack::rules::RuleSet>,
    params: &LearnParams,
    priors: &rccpack::priors::Priors,
) -> Result<rccpack::infer::Learned, rccpack::InferError> {
    let opts = rccpack::infer::LearnOptions {
        priors: Some(priors),
        ..Default::default()
    };
    rccpack::infer::learn_with(demos, statements, params, &opts)
}
