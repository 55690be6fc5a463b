//! # rccpack
//!
//! Learn spatial placement rules from a handful of demonstrations, show them
//! as readable `.rcc` rules, and lay out new objects so that the rules hold.
//!
//! The data flows one way:
//!
//! ```text
//! scene JSON ─► scene ─► relations ─► rules (.rcc) ─► eval (score, docs/language.md#the-score)
//!                                          │
//!                  demos ─► infer ─────────┤ learned .rcc
//!                                          ▼
//!                problem ─► synth (model ─► driver ─► engine) ─► scene
//!                                          │
//!                       eval re-checks every output scene
//! ```
//!
//! ## A scene, some rules, a score
//!
//! A [`Scene`] is a table (the *space*), a grid step and axis-aligned
//! rectangles of named classes; north is +y. Rules are Boolean formulas over
//! directional Region Connection Calculus relations lifted to classes:
//! `DR_N(B, R)` reads "every B is north of every R", `EC_W(G, *)` "every G
//! touches something on that thing's west side".
//!
//! ```
//! use rccpack::{evaluate, parse_rules, Contact, Scene};
//!
//! let scene = Scene::from_json(r#"{
//!   "space": {"width": 100, "height": 100},
//!   "objects": [
//!     {"id": "b1", "class": "B", "x": 0,  "y": 20, "width": 20, "height": 20},
//!     {"id": "r1", "class": "R", "x": 0,  "y": 0,  "width": 20, "height": 20},
//!     {"id": "r2", "class": "R", "x": 60, "y": 0,  "width": 20, "height": 20}
//!   ]}"#)?;
//! let rules = parse_rules(
//!     "rule blue_north_of_red: DR_N(B, R)\n\
//!      rule red_touches_red weight 2: EC_E(R, R) | EC_W(R, R)\n",
//! )?;
//! let report = evaluate(&scene, &rules, Contact::Point);
//! // b1 keeps its rule (weight 1); neither red touches the other (2 × 2).
//! assert_eq!((report.satisfied_weight, report.total_weight), (1.0, 5.0));
//! println!("score {:.2}", report.score); // score 0.20
//! assert_eq!(report.rules[1].violators, ["r1", "r2"]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Learning rules from demonstrations
//!
//! [`learn`] weighs every statement of the templates (or of a statement
//! set you give) against a null model of random layouts and keeps the ones
//! the demonstrations keep far more often than chance (docs/guide.md):
//!
//! ```
//! use rccpack::{learn, LearnParams, Scene};
//!
//! let demos = rccpack::scene::scenes_from_json(
//!     &std::fs::read_to_string("examples/box-packing/demos.json")?,
//! )?;
//! let params = LearnParams { samples: 200, ..LearnParams::default() };
//! let learned = learn(&demos, None, &params)?;
//! let rules = learned.rules();
//! assert!(rules.rules.iter().any(|r| r.name == "B_dr_n_R")); // blue north of red
//! print!("{}", learned.to_rcc()); // the `.rcc` file `rccpack learn` writes
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Placing new objects
//!
//! [`synthesize`] places every unplaced object of a problem on the grid so
//! that the hard rules hold and the score is as high as it can be (docs/guide.md#synthesis);
//! every layout it returns has passed the independent check
//! [`synth::verify_solution`].
//!
//! ```
//! use rccpack::{parse_rules, synthesize, Object, Scene, Space, Status, SynthOptions};
//!
//! let problem = Scene::new(
//!     Space { x: 0, y: 0, width: 60, height: 60 },
//!     10,
//!     vec![
//!         Object::fixed_at("wall", "W", 0, 0, 60, 10),
//!         Object::movable("r1", "R", 20, 20),
//!         Object::movable("b1", "B", 20, 20),
//!     ],
//! )?;
//! let rules = parse_rules(
//!     "rule red_on_wall: EC_N(R, W)\n\
//!      rule blue_on_red: EC_N(B, R)\n",
//! )?;
//! let result = synthesize(&problem, &rules, &SynthOptions::default())?;
//! assert_eq!(result.status, Status::Optimal);
//! let layout = result.scene.expect("a layout");
//! let red = &layout.objects[1];
//! assert_eq!(red.y, Some(10)); // on the wall
//! assert_eq!(result.evaluation.expect("scored").score, 1.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## The whole task
//!
//! A task folder holds `demos.json`, `problem.json` and optionally
//! `statements.rcc`; [`task::run`] learns, checks the rules against the
//! problem and places it with the demonstrations as the warm start and the
//! resemblance target (docs/guide.md#layouts-like-the-demonstrations) — what `rccpack run` does:
//!
//! ```
//! use rccpack::task::{self, RunOptions, Task};
//!
//! let task = Task::load("examples/box-packing")?;
//! let mut opts = RunOptions::default();
//! opts.learn.samples = 200;
//! opts.synth.stop = rccpack::stop::Stop::never().with_nodes(20_000);
//! let outcome = task::run(&task, &opts)?;
//! let layout = outcome.placement.result.scene.expect("a layout");
//! assert!(layout.is_complete());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Where things live
//!
//! - [`scene`]: geometry, the JSON format, validation with field paths.
//! - [`relations`]: the sixteen relations (`DR`, `EC`, `FL`, `AL` × `N S E
//!   W`) defined once in a table, contact modes, a `u16` of relation bits
//!   per ordered pair, class atoms.
//! - [`rules`]: the `.rcc` language — AST, parser (grammar in
//!   `grammar/rcc.pest`), checks, printer, diagnostics.
//! - [`shapes`]: group statements (`row(R)`, `column(R)`, `block(G)`,
//!   `group(B)`): the semantics the evaluator, learning and tests share.
//! - [`eval`]: the one evaluator and the score.
//! - [`infer`]: learning (docs/guide.md#learning).
//! - [`priors`]: priors per kind of statement learned across a library of
//!   tasks (`rccpack priors`, `--priors`).
//! - [`synth`]: synthesis of layouts; [`synth::emit`] writes the same model
//!   for other solvers.
//! - [`resemblance`]: docs/guide.md#layouts-like-the-demonstrations, the second objective.
//! - [`ask`]: the questions of docs/guide.md#questions, without I/O.
//! - [`task`]: the task folder and the whole pipeline.
//! - [`mod@sample`]: many distinct layouts that keep the rules (property tests,
//!   fuzzing); `proptest` strategies and `Arbitrary` impls behind the features
//!   of those names.
//! - [`render`]: SVG pictures; PNG with the `png` feature.
//! - [`limits`]: the documented limits on user-supplied numbers.
//! - [`stop`]: when to stop a computation (a deadline, a node budget, a
//!   cancel flag), taken by learning ([`infer::learn_with`]) and the pipeline.
//! - [`fsutil`]: the one atomic file writer, UTF-8 reading, the folder lock.
//! - `studio` (feature `studio`): the local web app. The benchmark suites
//!   are a crate of their own in the repository (`bench/`, `rccpack-bench`),
//!   built on this public API.
//!
//! ## Features
//!
//! The default features build the whole command-line tool. An embedder
//! writes `rccpack = { version = "0.1", default-features = false }` and gets
//! the core above (learning, evaluation, synthesis, SVG, the task pipeline)
//! with no web server, image or CLI crates; `png`, `studio` and `cli` add
//! the rest (see the README, "As a library").
//!
//! The command-line tool `rccpack` wraps these (`check`, `score`, `render`,
//! …); see docs/cli.md.
#![warn(unreachable_pub)]
#![warn(missing_docs)]

pub mod ask;
pub mod eval;
pub mod fsutil;
#[cfg(feature = "fuzzing")]
#[doc(hidden)]
pub mod fuzzing;
pub mod infer;
pub mod limits;
pub mod priors;
pub mod relations;
pub mod render;
pub mod resemblance;
pub mod rules;
pub mod sample;
pub mod scene;
pub mod shapes;
pub mod stop;
#[cfg(feature = "studio")]
pub mod studio;
pub mod synth;
pub mod task;

// The curated surface: what an embedder calls, one name per concept.
pub use eval::{evaluate, Evaluation, RuleReport};
pub use infer::{learn, InferError, LearnParams, Learned, Templates};
pub use relations::Contact;
pub use render::{render_svg, RenderOptions};
pub use rules::{parse_rules, Diagnostic, DiagnosticKind, Rule, RuleSet, RulesError};
pub use sample::{sample, Quality, Repair, SampleError, SampleOptions, Sampler};
pub use scene::{Object, Scene, SceneError, SceneErrorKind, Space};
pub use synth::{
    synthesize, Conflict, Resemblance, SolveStats, Status, SynthError, SynthOptions, SynthResult,
};
pub use task::{Task, TaskError};

/// The Rust examples of the README and the docs, compiled and run as
/// doctests so that a page cannot drift from the crate (the shell examples
/// run in `tests/docs.rs`).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
