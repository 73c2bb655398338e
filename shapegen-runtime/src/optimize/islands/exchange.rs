//! The processes an island model runs on: [`Exchange`], the three collective operations
//! it needs from them, and [`Alone`], the one process of a run that is not spread.

/// Why an [`Exchange`] failed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("exchange between processes failed: {0}")]
pub struct ExchangeError(pub String);

/// The processes one island-model run is spread over (as MPI ranks are), as the run
/// sees them: this process's rank among [`size`](Self::size), and three collective
/// operations on byte messages. Every process calls the operations in the same order;
/// each returns once all have called it.
///
/// The runtime holds one implementation, [`Alone`] (one process). The `shapegen`
/// command-line tool adds one over MPI; tests can run several processes' worth of
/// islands on threads with channels.
pub trait Exchange {
    /// This process's rank, from 0.
    fn rank(&self) -> usize;

    /// Number of processes.
    fn size(&self) -> usize;

    /// Gives `mine` to every process; returns every process's message, by rank.
    fn all_gather(&self, mine: Vec<u8>) -> Result<Vec<Vec<u8>>, ExchangeError>;

    /// Gives `mine` to rank 0, which gets every process's message, by rank; the others
    /// get `None`.
    fn gather(&self, mine: Vec<u8>) -> Result<Option<Vec<Vec<u8>>>, ExchangeError>;

    /// Sends `to_next` to the next process on the ring (rank + 1, the last to rank 0)
    /// and returns what the previous one sent.
    fn shift(&self, to_next: Vec<u8>) -> Result<Vec<u8>, ExchangeError>;
}

/// A run on one process: every operation gives back what it was given.
///
/// ```
/// use shapegen_runtime::optimize::islands::{Alone, Exchange};
///
/// let alone = Alone;
/// assert_eq!((alone.rank(), alone.size()), (0, 1));
/// assert_eq!(alone.shift(vec![7])?, vec![7]);
/// assert_eq!(alone.all_gather(vec![1, 2])?, vec![vec![1, 2]]);
/// # Ok::<(), shapegen_runtime::optimize::islands::ExchangeError>(())
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Alone;

impl Exchange for Alone {
    fn rank(&self) -> usize {
        0
    }

    fn size(&self) -> usize {
        1
    }

    fn all_gather(&self, mine: Vec<u8>) -> Result<Vec<Vec<u8>>, ExchangeError> {
        Ok(vec![mine])
    }

    fn gather(&self, mine: Vec<u8>) -> Result<Option<Vec<Vec<u8>>>, ExchangeError> {
        Ok(Some(vec![mine]))
    }

    fn shift(&self, to_next: Vec<u8>) -> Result<Vec<u8>, ExchangeError> {
        Ok(to_next)
    }
}
