//! Work while the person looks: the next question for both answers.
//!
//! While a question waits for its answer, [`Asker::look_ahead`] computes
//! the session after "acceptable" and after "not acceptable", each with its
//! next question, on threads of their own. The answer then picks the
//! branch computed for it ([`Lookahead::answer`]): the wait the person sees
//! is what is left of that branch, often nothing. The other branch is
//! stopped and dropped; it writes nothing (the caller writes the files of
//! the branch it gets back, as it would without a look-ahead).
//!
//! A branch is computed exactly as the session would compute it after the
//! answer (the same budgets, the same seed), so the questions are the same
//! with and without a look-ahead and on any number of threads (tested);
//! only the question budget's wall-clock cap, a safety net, depends on how
//! busy the machine is.

use super::session::{AskError, Asker, Question};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;

type Branch = Result<(Asker, Option<Question>), AskError>;

/// The sessions after each answer to one question, being computed.
pub struct Lookahead {
    /// `[not acceptable, acceptable]`.
    branches: [Option<Pending>; 2],
}

enum Pending {
    /// Computed on a thread; the flag stops its solves.
    Thread(JoinHandle<Branch>, Arc<AtomicBool>),
    /// Computed when the answer comes (a look-ahead on one thread).
    Later(Box<(Asker, Question)>),
}

/// The session after answering `q` with `accepted`, and its next question.
fn branch(mut asker: Asker, q: &Question, accepted: bool) -> Branch {
    asker.answer(q, accepted)?;
    let next = asker.next_question()?;
    Ok((asker, next))
}

impl Asker {
    /// Start computing the session after each answer to `q` (the question
    /// just returned by [`Asker::next_question`]) on two threads, or, with
    /// `threads` below 2, nothing until the answer comes.
    pub fn look_ahead(&self, q: &Question, threads: usize) -> Lookahead {
        let pending = |accepted: bool| {
            if threads < 2 {
                return Pending::Later(Box::new((self.clone(), q.clone())));
            }
            let cancel = Arc::new(AtomicBool::new(false));
            let mut asker = self.clone();
            asker.set_cancel(Some(cancel.clone()));
            let q = q.clone();
            let handle = std::thread::spawn(move || {
                let (mut asker, next) = branch(asker, &q, accepted)?;
                asker.set_cancel(None);
                Ok((asker, next))
            });
            Pending::Thread(handle, cancel)
        };
        Lookahead {
            branches: [Some(pending(false)), Some(pending(true))],
        }
    }
}

impl Lookahead {
    /// The session after the answer `accepted` and its next question (waits
    /// for its branch when it is not ready yet); the other branch is
    /// stopped.
    pub fn answer(mut self, accepted: bool) -> Branch {
        if let Some(Pending::Thread(_, cancel)) = &self.branches[usize::from(!accepted)] {
            cancel.store(true, Ordering::SeqCst);
        }
        match self.branches[usize::from(accepted)].take() {
            Some(Pending::Thread(handle, _)) => match handle.join() {
                Ok(b) => b,
                Err(panic) => std::panic::resume_unwind(panic),
            },
            Some(Pending::Later(b)) => {
                let (asker, q) = *b;
                branch(asker, &q, accepted)
            }
            None => unreachable!("each branch is taken once"),
        }
    }
}

impl Drop for Lookahead {
    fn drop(&mut self) {
        // Branches not taken stop their solves; their threads end on their
        // own (learning checks the same flag before each random scene).
        for b in self.branches.iter().flatten() {
            if let Pending::Thread(_, cancel) = b {
                cancel.store(true, Ordering::SeqCst);
            }
        }
    }
}
