//! # rccpack
//!
//! Learn spatial placement rules from a handful of demonstrations, show them
//! as readable `.rcc` rules, and lay out new objects so that the rules hold.
//!
//! The data flows one way:
//!
//! ```text
//! scene JSON ─► scene ─► relations ─► rules (.rcc) ─► eval (score, SPEC §6)
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
//! A [`scene::Scene`] is a table (the *space*), a grid step and axis-aligned
//! rectangles of named classes; north is +y. Rules are Boolean formulas over
//! directional Region Connection Calculus relations lifted to classes:
//! `DR_N(B, R)` reads "every B is north of every R", `EC_W(G, *)` "every G
//! touches something on that thing's west side".
//!
//! ```
//! use rccpack::{eval::evaluate, relations::Contact, rules::parse_rules, scene::Scene};
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
//! ## Where things live
//!
//! - [`scene`]: geometry, the JSON format, validation with field paths.
//! - [`relations`]: the eight relations, contact modes, one byte of relation
//!   bits per ordered pair, class atoms.
//! - [`rules`]: the `.rcc` language — AST, parser (grammar in
//!   `grammar/rcc.pest`), checks, printer, diagnostics.
//! - [`eval`]: the one evaluator and the §6 score.
//! - [`render`]: SVG and PNG pictures.
//! - [`synth`]: synthesis of layouts.
//! - [`limits`]: the documented limits on user-supplied numbers.
//! - [`fsutil`]: the one atomic file writer every writer uses.
//!
//! The command-line tool `rccpack` wraps these (`check`, `score`, `render`,
//! …); see the README.
#![warn(missing_docs)]

pub mod ask;
#[cfg(feature = "bench")]
pub mod bench;
pub mod eval;
pub mod fsutil;
#[cfg(feature = "fuzzing")]
#[doc(hidden)]
pub mod fuzzing;
pub mod infer;
pub mod limits;
pub mod relations;
pub mod render;
pub mod resemblance;
pub mod rules;
pub mod scene;
#[cfg(feature = "studio")]
pub mod studio;
pub mod synth;
pub mod task;

// The curated surface: what an embedder calls, one name per concept.
pub use eval::{evaluate, Evaluation, RuleReport};
pub use infer::{learn, InferError, LearnParams, Learned, Templates};
pub use relations::Contact;
pub use render::{render_svg, RenderOptions};
pub use rules::{parse_rules, Diagnostic, Rule, RuleSet, RulesError};
pub use scene::{Object, Scene, SceneError, Space};
pub use synth::{
    synthesize, Conflict, Resemblance, SolveStats, Status, SynthError, SynthOptions, SynthResult,
};
pub use task::{Task, TaskError};
