//! Several processes' worth of islands on threads: an `Exchange` over channels, and a
//! helper running one closure per rank.

use std::collections::VecDeque;
use std::sync::Mutex;
use std::sync::mpsc::{Receiver, Sender, channel};

use shapegen_runtime::optimize::islands::{Exchange, ExchangeError};

/// A message and the rank that sent it.
type Message = (usize, Vec<u8>);

/// A rank's inbox: the channel, and what arrived from each rank but was not taken yet.
struct Inbox {
    receiver: Receiver<Message>,
    pending: Vec<VecDeque<Vec<u8>>>,
}

/// One rank of a group of threads exchanging through channels. Messages between two
/// ranks arrive in the order they were sent, so each collective operation takes, from
/// each sender, the next message it sent.
pub struct Threads {
    rank: usize,
    to: Vec<Sender<Message>>,
    inbox: Mutex<Inbox>,
}

impl Threads {
    /// The `size` ranks of one group.
    pub fn group(size: usize) -> Vec<Threads> {
        let (to, from): (Vec<_>, Vec<_>) = (0..size).map(|_| channel()).unzip();
        from.into_iter()
            .enumerate()
            .map(|(rank, receiver)| Threads {
                rank,
                to: to.clone(),
                inbox: Mutex::new(Inbox {
                    receiver,
                    pending: vec![VecDeque::new(); size],
                }),
            })
            .collect()
    }

    fn send(&self, to: usize, bytes: Vec<u8>) -> Result<(), ExchangeError> {
        self.to[to]
            .send((self.rank, bytes))
            .map_err(|_| ExchangeError(format!("rank {to} is gone")))
    }

    fn receive(&self, from: usize) -> Result<Vec<u8>, ExchangeError> {
        let inbox = &mut *self.inbox.lock().unwrap();
        while inbox.pending[from].is_empty() {
            let (sender, bytes) = inbox
                .receiver
                .recv()
                .map_err(|_| ExchangeError("every other rank is gone".into()))?;
            inbox.pending[sender].push_back(bytes);
        }
        Ok(inbox.pending[from].pop_front().unwrap())
    }
}

impl Exchange for Threads {
    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.to.len()
    }

    fn all_gather(&self, mine: Vec<u8>) -> Result<Vec<Vec<u8>>, ExchangeError> {
        for to in 0..self.size() {
            self.send(to, mine.clone())?;
        }
        (0..self.size()).map(|from| self.receive(from)).collect()
    }

    fn gather(&self, mine: Vec<u8>) -> Result<Option<Vec<Vec<u8>>>, ExchangeError> {
        self.send(0, mine)?;
        if self.rank != 0 {
            return Ok(None);
        }
        (0..self.size())
            .map(|from| self.receive(from))
            .collect::<Result<_, _>>()
            .map(Some)
    }

    fn shift(&self, to_next: Vec<u8>) -> Result<Vec<u8>, ExchangeError> {
        let size = self.size();
        self.send((self.rank + 1) % size, to_next)?;
        self.receive((self.rank + size - 1) % size)
    }
}

/// Runs `work(exchange)` for every rank of a group of `size` on its own thread, and
/// returns what each returned, by rank.
pub fn on_ranks<T: Send>(size: usize, work: impl Fn(Threads) -> T + Sync) -> Vec<T> {
    std::thread::scope(|scope| {
        let handles: Vec<_> = Threads::group(size)
            .into_iter()
            .map(|exchange| scope.spawn(|| work(exchange)))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    })
}
