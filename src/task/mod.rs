//! A task folder and the whole pipeline on it (docs/cli.md `run`): learn rules
//! from the demonstrations, check them against the problem, and place the
//! problem's objects with the demonstrations as the like-scenes and the warm
//! start.
//!
//! `rccpack run`, `rccpack ask` and the studio call this module instead of
//! re-implementing the steps; an embedder calls it the same way:
//!
//! ```
//! use rccpack::task::{self, RunOptions, Task};
//!
//! let task = Task::load("examples/box-packing")?;
//! let mut opts = RunOptions::default();
//! opts.learn.samples = 200; // a quick run; the default is 1000
//! opts.synth.stop = rccpack::stop::Stop::never().with_nodes(20_000);
//! let outcome = task::run(&task, &opts)?;
//! println!("{} rules learned", outcome.rules.rules.len());
//! let layout = outcome.placement.result.scene.as_ref().expect("a layout");
//! assert!(layout.is_complete());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The folder's file names are the constants of [`files`].

pub mod files;
pub mod folder;
pub mod library;
pub mod session;

use crate::infer::{InferError, LearnOptions, LearnParams, Learned};
use crate::resemblance::ResemblanceTarget;
use crate::rules::{check_landmarks, missing_classes, parse_rules, RuleSet, RulesError};
use crate::scene::{scenes_from_json, Scene, SceneError};
use crate::synth::{synthesize, SynthError, SynthOptions, SynthResult};
use std::path::{Path, PathBuf};

/// Why the pipeline stopped. Every variant that comes from a file names it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TaskError {
    /// A file could not be read (or is not UTF-8).
    #[error("{}: cannot read file: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file is not UTF-8 text.
    #[error("{}: {source}", path.display())]
    NotUtf8 {
        /// The file.
        path: PathBuf,
        /// Where the first bad byte is.
        source: crate::fsutil::NotUtf8,
    },
    /// A scene file is not a valid scene (or array of scenes).
    #[error("{}: {source}", path.display())]
    Scene {
        /// The file.
        path: PathBuf,
        /// The error, with its JSON field path.
        source: SceneError,
    },
    /// The statement file is not valid `.rcc`, or names a landmark a
    /// demonstration lacks. [`RulesError::render`] with `text` draws the
    /// carets.
    #[error("{}: {source}", path.display())]
    Rules {
        /// The file.
        path: PathBuf,
        /// Its text, for rendering the diagnostics.
        text: String,
        /// The diagnostics.
        source: RulesError,
    },
    /// Learning refused the demonstrations or statements, or its time ran
    /// out ([`InferError::TimeLimit`]).
    #[error(transparent)]
    Learn(#[from] InferError),
    /// The rules name a landmark (`@ID`) the problem has no fixed object
    /// for.
    #[error("the learned rules name a landmark the problem lacks: {0}")]
    Landmark(RulesError),
    /// Synthesis refused the problem.
    #[error(transparent)]
    Synth(#[from] SynthError),
}

/// A task: the demonstrations, the optional statement set to learn with, and
/// the problem to place.
#[derive(Debug, Clone)]
pub struct Task {
    /// The demonstrations (`demos.json`).
    pub demos: Vec<Scene>,
    /// The statements to learn (`statements.rcc`); `None`: the templates.
    pub statements: Option<RuleSet>,
    /// The problem (`problem.json`).
    pub problem: Scene,
}

/// Read a whole UTF-8 text file (a leading byte-order mark is dropped).
pub fn read_text(path: &Path) -> Result<String, TaskError> {
    read_text_at_most(path, usize::MAX)
}

/// [`read_text`] that reads at most `max` bytes: a longer file (or an
/// endless device, `/dev/zero`) is refused once `max` is passed, before
/// it fills the memory.
pub fn read_text_at_most(path: &Path, max: usize) -> Result<String, TaskError> {
    use std::io::Read as _;
    let read = |path: &Path| -> std::io::Result<Vec<u8>> {
        let f = std::fs::File::open(path)?;
        let len = f.metadata().ok().filter(|m| m.is_file()).map(|m| m.len());
        let too_large = |size: String| {
            std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "the file is {size} bytes; expected at most {max} bytes ({} MiB)",
                    max >> 20
                ),
            )
        };
        if let Some(len) = len.filter(|&l| l > max as u64) {
            return Err(too_large(len.to_string()));
        }
        let mut bytes = Vec::new();
        f.take((max as u64).saturating_add(1))
            .read_to_end(&mut bytes)?;
        if bytes.len() > max {
            return Err(too_large(format!("larger than {max}")));
        }
        Ok(bytes)
    };
    let bytes = read(path).map_err(|source| TaskError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    crate::fsutil::utf8_text(bytes).map_err(|source| TaskError::NotUtf8 {
        path: path.to_path_buf(),
        source,
    })
}

/// Read a scene JSON file, at most [`crate::limits::MAX_SCENE_BYTES`].
pub fn read_scene_text(path: &Path) -> Result<String, TaskError> {
    read_text_at_most(path, crate::limits::MAX_SCENE_BYTES)
}

/// Read a scene file or an array of scenes.
pub fn read_scenes(path: &Path) -> Result<Vec<Scene>, TaskError> {
    scenes_from_json(&read_scene_text(path)?).map_err(|source| TaskError::Scene {
        path: path.to_path_buf(),
        source,
    })
}

/// Read a demonstrations file as measured
/// ([`crate::scene::measured`]): positions snapped to the grid with the
/// default tolerance, exact on-grid files read as they are.
pub fn read_demos(path: &Path) -> Result<Vec<Scene>, TaskError> {
    crate::scene::measured::measured_from_json(&read_scene_text(path)?, None)
        .map(|m| m.scenes)
        .map_err(|source| TaskError::Scene {
            path: path.to_path_buf(),
            source,
        })
}

/// Read one scene.
pub fn read_scene(path: &Path) -> Result<Scene, TaskError> {
    Scene::from_json(&read_scene_text(path)?).map_err(|source| TaskError::Scene {
        path: path.to_path_buf(),
        source,
    })
}

/// Read a statement file and check that every landmark it names is a fixed
/// object of every demonstration.
pub fn read_statements(path: &Path, demos: &[Scene]) -> Result<RuleSet, TaskError> {
    let text = read_text(path)?;
    let checked = parse_rules(&text).and_then(|set| {
        demos
            .iter()
            .try_for_each(|d| check_landmarks(&set, d))
            .map(|()| set)
    });
    checked.map_err(|source| TaskError::Rules {
        path: path.to_path_buf(),
        text,
        source,
    })
}

impl Task {
    /// Read a task folder: `demos.json` (as measured: [`read_demos`]),
    /// `problem.json` and, when present, `statements.rcc` ([`files`]).
    pub fn load(dir: impl AsRef<Path>) -> Result<Task, TaskError> {
        let dir = dir.as_ref();
        let demos = read_demos(&dir.join(files::DEMOS))?;
        let statements_path = dir.join(files::STATEMENTS);
        let statements = if statements_path.exists() {
            Some(read_statements(&statements_path, &demos)?)
        } else {
            None
        };
        let problem = read_scene(&dir.join(files::PROBLEM))?;
        Ok(Task {
            demos,
            statements,
            problem,
        })
    }
}

/// Which scenes the layout should resemble (docs/guide.md#layouts-like-the-demonstrations).
#[derive(Debug, Clone, Default)]
#[non_exhaustive]
pub enum Like {
    /// The task's demonstrations (the default of `rccpack run`).
    #[default]
    Demos,
    /// These scenes.
    Scenes(Vec<Scene>),
    /// Score only.
    Off,
}

/// Options of [`run`] and [`place`].
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Learning parameters.
    pub learn: LearnParams,
    /// Synthesis options. `stop` covers the whole of [`run`] (learning
    /// stops at its deadline and cancel flag too); `contact` is the learning's
    /// ([`LearnParams::contact`]); `like` and `warm_start` are set from
    /// [`RunOptions::like`] and the demonstrations.
    pub synth: SynthOptions,
    /// What the layout should resemble.
    pub like: Like,
    /// Priors learned across tasks ([`crate::priors`]); `None`: the
    /// uniform prior of [`LearnParams::prior`].
    pub priors: Option<std::sync::Arc<crate::priors::Priors>>,
}

/// A placed problem.
#[derive(Debug, Clone)]
pub struct Placement {
    /// The synthesis result (status, layout, evaluation, conflict, stats).
    pub result: SynthResult,
    /// Classes the rules name that the problem lacks (docs/language.md#classes-a-scene-lacks: noted, and
    /// the rules about them hold as docs/language.md#class-rules says).
    pub missing_classes: Vec<String>,
    /// The resemblance target used, if any (e.g. for
    /// [`crate::render::RenderOptions::like`]).
    pub like: Option<ResemblanceTarget>,
}

/// What [`run`] produced.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Everything learning found (write it with [`Learned::to_rcc`] and
    /// [`Learned::report_json`]).
    pub learned: Learned,
    /// The learned rules.
    pub rules: RuleSet,
    /// The placed problem.
    pub placement: Placement,
}

/// Place `problem` under `rules`: the landmarks are checked, the
/// demonstrations are the warm start and (with [`Like::Demos`]) the
/// resemblance target.
pub fn place(
    problem: &Scene,
    rules: &RuleSet,
    demos: &[Scene],
    like: &Like,
    opts: &SynthOptions,
) -> Result<Placement, TaskError> {
    let missing = missing_classes(rules, problem);
    check_landmarks(rules, problem).map_err(TaskError::Landmark)?;
    let like = match like {
        Like::Demos => Some(ResemblanceTarget::new(demos)),
        Like::Scenes(s) => Some(ResemblanceTarget::new(s)),
        Like::Off => None,
    };
    let opts = SynthOptions {
        like: like.clone(),
        warm_start: demos.to_vec(),
        ..opts.clone()
    };
    let result = synthesize(problem, rules, &opts)?;
    Ok(Placement {
        result,
        missing_classes: missing,
        like,
    })
}

/// Learn the task's rules ([`crate::infer::learn_with`]): priors and when
/// to stop in `opts`.
pub fn learn(
    task: &Task,
    params: &LearnParams,
    opts: &LearnOptions<'_>,
) -> Result<Learned, TaskError> {
    Ok(crate::infer::learn_with(
        &task.demos,
        task.statements.as_ref(),
        params,
        opts,
    )?)
}

/// The whole pipeline: [`learn`], then [`place`] with what is left of
/// `opts.synth.stop` (one stop for the whole pipeline: its deadline and
/// cancel flag stop learning too; its node budget is synthesis').
pub fn run(task: &Task, opts: &RunOptions) -> Result<Outcome, TaskError> {
    let learn_opts = LearnOptions {
        priors: opts.priors.as_deref(),
        stop: opts.synth.stop.clone().nodes_at_most(None),
        ..LearnOptions::default()
    };
    let learned = learn(task, &opts.learn, &learn_opts)?;
    let rules = learned.rules();
    let synth = SynthOptions {
        contact: opts.learn.contact,
        ..opts.synth.clone()
    };
    let placement = place(&task.problem, &rules, &task.demos, &opts.like, &synth)?;
    Ok(Outcome {
        learned,
        rules,
        placement,
    })
}
