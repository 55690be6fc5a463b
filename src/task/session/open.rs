//! Opening a session: the folder lock, the inputs and `answers.json` read,
//! the loop resumed from the answers, the start's files written.

use super::{
    ask_err, ask_path, disk_versions, Locking, Session, SessionError, SessionInputs, SessionOptions,
};
use crate::ask::{AnswersFile, Asker};
use crate::fsutil::DirLock;
use crate::task::{files, read_text};
use std::path::Path;

fn take_lock(dir: &Path) -> Result<DirLock, SessionError> {
    match DirLock::try_lock(dir) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err(SessionError::Locked {
            dir: dir.to_path_buf(),
        }),
        Err(source) => Err(SessionError::Lock {
            path: dir.join(crate::fsutil::LOCK_FILE),
            source,
        }),
    }
}

impl Session {
    /// Start or resume the session of the task folder `dir`: take the folder
    /// lock ([`Locking::Session`]), read `problem.json`, `demos.json`,
    /// `statements.rcc` (if any) and `answers.json` (if any), learn, and
    /// write `learned.rcc` (and `demos.json` when an abort had kept an
    /// accepted probe out of it) as `rccpack ask` does at its start
    /// ([`files::write_session_start`]).
    pub fn open(dir: impl AsRef<Path>, opts: SessionOptions) -> Result<Session, SessionError> {
        let dir = dir.as_ref();
        let lock = if opts.save && opts.locking == Locking::Session {
            Some(take_lock(dir)?)
        } else {
            None
        };
        let inputs = SessionInputs::read(dir)?;
        let mut s = Session::open_with(dir, inputs, opts)?;
        s._lock = lock;
        Ok(s)
    }

    /// [`Session::open`] with the task's inputs read by the caller (the
    /// studio reads them with its own errors); `answers.json` is read here.
    /// With [`Locking::Session`] the caller's lock is not taken: hold it, or
    /// use [`Session::open`].
    pub fn open_with(
        dir: impl AsRef<Path>,
        inputs: SessionInputs,
        opts: SessionOptions,
    ) -> Result<Session, SessionError> {
        let dir = dir.as_ref().to_path_buf();
        let answers_path = dir.join(files::ANSWERS);
        let answers = if opts.save && answers_path.exists() {
            AnswersFile::from_json(&read_text(&answers_path)?)
                .map_err(|source| SessionError::Answers {
                    path: answers_path.clone(),
                    source,
                })?
                .answers
        } else {
            Vec::new()
        };
        let resumed = answers.len();
        let SessionInputs {
            problem,
            demos,
            statements,
        } = inputs;
        let asker = Asker::new(
            problem.clone(),
            demos.scenes.clone(),
            statements.clone(),
            answers,
            opts.ask.clone(),
        )
        .map_err(|e| ask_err(ask_path(&dir, &e))(e))?;
        let backup = if opts.save {
            files::write_session_start(&dir, &asker, &demos, resumed).map_err(
                |(file, source)| SessionError::Write {
                    path: dir.join(file),
                    source,
                },
            )?
        } else {
            false
        };
        let versions = if opts.save {
            disk_versions(&dir)?
        } else {
            Default::default()
        };
        Ok(Session {
            dir,
            _lock: None,
            problem,
            statements,
            opts,
            asker,
            open: None,
            prepared: None,
            resumed,
            asked_now: 0,
            out_of_budget: false,
            backup,
            versions,
            demos_read: demos,
        })
    }
}
