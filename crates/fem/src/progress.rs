//! Watching a non-linear solve while it runs (the live progress of
//! `aster run`): the Newton loop reports each iteration, each converged
//! increment and each step cut to the observer the caller installed for the
//! duration of a closure ([`observe`]). Without an observer a report costs
//! one thread-local read. The observer only watches: it cannot change the
//! solve.

use std::cell::RefCell;

/// One Newton iteration of an increment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration {
    /// The instant of the increment.
    pub time: f64,
    /// Newton iterations of the increment so far (code_aster's count: the
    /// passes that only move the contact active set are not counted).
    pub newton: usize,
    pub resi_glob_rela: f64,
    pub resi_glob_maxi: f64,
    /// Updates of the contact/unilateral active set in the increment.
    pub contact_iterations: usize,
    /// Geometric re-pairings in the increment (`REAC_GEOM`).
    pub pairings: usize,
    /// The iteration moved the active set or the pairing (another pass
    /// follows on the same Newton iterate).
    pub active_set_changed: bool,
}

/// What a solve reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    Iteration(Iteration),
    /// An increment converged at `time` after `iterations` Newton
    /// iterations.
    Converged {
        time: f64,
        iterations: usize,
    },
    /// The increment `from → to` failed and is cut in `pieces`
    /// (`DEFI_LIST_INST/ECHEC`).
    Cut {
        from: f64,
        to: f64,
        pieces: usize,
    },
    /// The increment `from → to` converged with a penetration beyond
    /// `PENE_MAXI`: the penalty was raised and the increment is redone
    /// (`DEFI_LIST_INST/ECHEC`, `ACTION='ADAPT_COEF_PENA'`).
    Redo {
        from: f64,
        to: f64,
        penetration: f64,
    },
}

/// Receives the events of a solve.
pub trait Observer {
    fn event(&mut self, event: &Event);
}

thread_local! {
    static OBSERVER: RefCell<Option<Box<dyn Observer>>> = const { RefCell::new(None) };
}

/// Runs `body` with `observer` receiving the events of the solves it makes
/// on this thread; gives the observer back with the result.
pub fn observe<R>(
    observer: Box<dyn Observer>,
    body: impl FnOnce() -> R,
) -> (R, Option<Box<dyn Observer>>) {
    let previous = OBSERVER.with(|o| o.borrow_mut().replace(observer));
    let result = body();
    let mine = OBSERVER.with(|o| std::mem::replace(&mut *o.borrow_mut(), previous));
    (result, mine)
}

/// Reports an event to the installed observer, if any.
pub(crate) fn emit(event: Event) {
    OBSERVER.with(|o| {
        if let Ok(mut o) = o.try_borrow_mut() {
            if let Some(obs) = o.as_mut() {
                obs.event(&event);
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::rc::Rc;

    struct Count(Rc<RefCell<Vec<Event>>>);
    impl Observer for Count {
        fn event(&mut self, e: &Event) {
            self.0.borrow_mut().push(*e);
        }
    }

    #[test]
    fn events_reach_the_observer_only_inside_observe() {
        let seen = Rc::new(RefCell::new(Vec::new()));
        emit(Event::Converged {
            time: 0.5,
            iterations: 1,
        });
        let ((), back) = observe(Box::new(Count(seen.clone())), || {
            emit(Event::Converged {
                time: 1.0,
                iterations: 2,
            })
        });
        emit(Event::Converged {
            time: 2.0,
            iterations: 3,
        });
        assert!(back.is_some());
        assert_eq!(
            *seen.borrow(),
            vec![Event::Converged {
                time: 1.0,
                iterations: 2
            }]
        );
    }
}
