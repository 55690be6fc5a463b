//! The questions and their answers: the next question shown (its probe
//! files written), an answer journaled and applied, the last answer undone.

use super::{
    ask_err, ask_path, disk_versions, write_err, write_probe_files, Open, Session, SessionError,
    Shown,
};
use crate::ask::{Answer, AnswersFile, Asker};
use crate::task::files;

impl Session {
    /// The next question, its probe written to `probes/probe-N.json` and
    /// drawn to `probes/probe-N.png` (when saving) as `rccpack ask` does;
    /// `None` when every held rule is settled, or when the question budget
    /// is spent ([`Session::out_of_budget`]; no probe file is written then).
    /// Asking again before answering returns the same question.
    pub fn next_question(&mut self) -> Result<Option<Shown>, SessionError> {
        if let Some(open) = &self.open {
            return Ok(Some(open.shown.clone()));
        }
        let next = match self.prepared.take() {
            Some(q) => q,
            None => self
                .asker
                .next_question()
                .map_err(ask_err(self.dir.join(files::PROBLEM)))?,
        };
        let Some(question) = next else {
            return Ok(None);
        };
        if self.opts.max_questions.is_some_and(|m| self.asked_now >= m) {
            self.out_of_budget = true;
            self.prepared = Some(Some(question));
            return Ok(None);
        }
        let number = self.asker.answers().len() + 1;
        let (json, png) = if self.opts.save && self.opts.probe_files {
            let (j, p) = write_probe_files(
                &self.dir,
                self.asker.held(),
                &question,
                number,
                self.opts.ask.learn.contact,
            )?;
            (Some(j), Some(p))
        } else {
            (None, None)
        };
        let ahead = self
            .asker
            .look_ahead(&question, self.opts.lookahead_threads);
        let shown = Shown {
            question,
            number,
            json,
            png,
        };
        self.open = Some(Open {
            shown: shown.clone(),
            ahead,
        });
        Ok(Some(shown))
    }

    /// Refuse to write when a file changed on disk since the session read
    /// or wrote it.
    pub(super) fn check_unchanged(&self) -> Result<(), SessionError> {
        if self.files_changed()? {
            return Err(SessionError::Changed {
                dir: self.dir.clone(),
            });
        }
        Ok(())
    }

    /// Answer the open question, about `rule` (docs/guide.md#questions):
    /// accepted → the probe becomes a demonstration and learning is redone;
    /// rejected → the rule is confirmed. When saving, the answer is
    /// journaled in `answers.json` before it is applied, then `demos.json`
    /// (accepted only) and `learned.rcc` are written, each atomically.
    pub fn answer(&mut self, rule: &str, accepted: bool) -> Result<&Answer, SessionError> {
        let open_rule = self.open.as_ref().map(|o| o.shown.question.rule.clone());
        if open_rule.as_deref() != Some(rule) {
            return Err(SessionError::NotOpen {
                rule: rule.to_string(),
                open: open_rule,
            });
        }
        if self.opts.save {
            // Before the question is taken: refused, it stays open.
            self.check_unchanged()?;
        }
        let open = self.open.take().expect("checked above");
        if self.opts.save {
            let mut answers = self.asker.answers().to_vec();
            answers.push(self.asker.answer_record(&open.shown.question, accepted));
            files::atomic_write(
                &self.dir,
                files::ANSWERS,
                &AnswersFile { answers }.to_json(),
            )
            .map_err(write_err(self.dir.join(files::ANSWERS)))?;
            self.versions = disk_versions(&self.dir)?;
        }
        let (asker, next) = open
            .ahead
            .answer(accepted)
            .map_err(|e| ask_err(ask_path(&self.dir, &e))(e))?;
        self.asker = asker;
        self.prepared = Some(next);
        self.asked_now += 1;
        if self.opts.save {
            self.check_unchanged()?;
            files::write_after_answer(&self.dir, &self.asker, &self.demos_read, accepted).map_err(
                |(file, source)| SessionError::Write {
                    path: self.dir.join(file),
                    source,
                },
            )?;
            self.versions = disk_versions(&self.dir)?;
        }
        Ok(self.asker.answers().last().expect("just answered"))
    }

    /// Take back the last answer (of this session or an earlier one): the
    /// loop restarts from the answers before it, as a resumed session
    /// would (an accepted probe leaves the demonstrations again), and the
    /// files are rewritten. `None` when nothing was answered. What earlier
    /// checks found is not kept, so the next question is the one a resumed
    /// session asks (the same as before unless a check reaches its node
    /// budget).
    pub fn undo(&mut self) -> Result<Option<Answer>, SessionError> {
        let mut answers = self.asker.answers().to_vec();
        let Some(last) = answers.pop() else {
            return Ok(None);
        };
        if self.opts.save {
            self.check_unchanged()?;
        }
        let mut demos = self.asker.demos().to_vec();
        if last.accepted && last.demo == Some(demos.len().saturating_sub(1)) {
            demos.pop();
        }
        let asker = Asker::new(
            self.problem.clone(),
            demos,
            self.statements.clone(),
            answers,
            self.opts.ask.clone(),
        )
        .map_err(ask_err(self.dir.join(files::ANSWERS)))?;
        self.asker = asker;
        self.open = None;
        self.prepared = None;
        self.asked_now = self.asked_now.saturating_sub(1);
        self.out_of_budget = false;
        if self.opts.save {
            let file = AnswersFile {
                answers: self.asker.answers().to_vec(),
            };
            let dir = &self.dir;
            files::atomic_write(dir, files::ANSWERS, &file.to_json())
                .map_err(write_err(dir.join(files::ANSWERS)))?;
            if last.accepted {
                files::atomic_write(
                    dir,
                    files::DEMOS,
                    &self.demos_read.to_json(self.asker.demos()),
                )
                .map_err(write_err(dir.join(files::DEMOS)))?;
            }
            files::atomic_write(dir, files::LEARNED, &self.asker.learned_rcc())
                .map_err(write_err(dir.join(files::LEARNED)))?;
            self.versions = disk_versions(&self.dir)?;
        }
        Ok(Some(last))
    }
}
