#pragma once
// The processes of one run. Started under `mpirun -np N` (and built with MPI), a simulation is
// split over N ranks that exchange flat records each step: ghosts, agents crossing a border, draw
// records gathered on rank 0. Without mpirun, or built without MPI, there is one rank and every
// call below is a local copy, so the same program runs either way.
//
// Every exchange is non-blocking with a deadline: a rank that died or hangs is named in a
// RankError within the timeout instead of leaving the others waiting forever. One thread at a time
// calls MPI (MPI_THREAD_SERIALIZED): the frame loop may step on a worker thread while the main
// thread draws, but parallel loops inside a rank never call it.

#include <chrono>
#include <cstddef>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace throng::sim {

/// A message's bytes.
using Bytes = std::vector<std::byte>;

/// A rank that did not take part in time, or sent a message that cannot be read.
class RankError : public std::runtime_error {
public:
    /// An error about rank `rank`.
    RankError(int rank, const std::string& what) : std::runtime_error(what), rank_(rank) {}
    /// The rank at fault.
    int rank() const { return rank_; }

private:
    int rank_;
};

/// This process's place among the ranks of the run, and collective exchanges between them.
class Ranks {
public:
    /// Joins the run: when Throng was built with MPI and the program was started by mpirun, starts
    /// MPI (once per process; it is finalised at exit) and takes this process's rank in its world;
    /// otherwise one rank, and MPI is never touched. `timeout` bounds how long any exchange waits
    /// for another rank. Throws std::invalid_argument if it is not positive.
    explicit Ranks(std::chrono::milliseconds timeout = std::chrono::seconds(30));
    Ranks(const Ranks&) = delete;
    Ranks& operator=(const Ranks&) = delete;

    /// Whether this build of Throng can run across ranks.
    static bool mpiAvailable();
    /// Whether this process was started by an MPI launcher (mpirun, mpiexec).
    static bool launchedByMpi();
    /// This process's rank, 0 to size() - 1.
    int rank() const { return rank_; }
    /// Number of ranks.
    int size() const { return size_; }
    /// How long an exchange waits for another rank.
    std::chrono::milliseconds timeout() const { return timeout_; }
    /// Sets that bound. Throws std::invalid_argument if it is not positive.
    void setTimeout(std::chrono::milliseconds timeout);

    /// Every rank sends `outgoing[r]` to rank r (outgoing.size() == size(); its own entry is kept)
    /// and receives what each rank sent it, indexed by sender. Collective: every rank calls it with
    /// the same `tag` (0 to 9999); `what` names the exchange in errors. Throws RankError naming the
    /// first rank that sent nothing within the timeout, std::invalid_argument for a bad argument.
    std::vector<Bytes> exchange(std::span<const Bytes> outgoing, int tag, std::string_view what);
    /// Rank 0 receives every rank's `mine` (indexed by rank); the others get an empty list.
    /// Collective, as exchange().
    std::vector<Bytes> gather(const Bytes& mine, int tag, std::string_view what);
    /// Every rank receives every rank's `mine` (indexed by rank; its own included), each message
    /// sent once per other rank from the one buffer. Collective, as exchange().
    std::vector<Bytes> allGather(const Bytes& mine, int tag, std::string_view what);
    /// Every rank receives rank 0's `fromRoot` (ignored elsewhere). Collective, as exchange().
    Bytes broadcast(const Bytes& fromRoot, int tag, std::string_view what);
    /// After a RankError this rank cannot exchange again (messages of the failed call may still be
    /// in flight, reading the buffers given): report the error and abort().
    ///
    /// Stops every rank of the run (MPI_Abort) with exit code `code`, after the caller reported why.
    /// Without MPI, exits this process.
    [[noreturn]] void abort(int code);

    /// Bytes this rank sent to other ranks so far (message payloads and their size headers).
    std::size_t bytesSent() const { return bytesSent_; }

private:
    int rank_ = 0;
    int size_ = 1;
    std::chrono::milliseconds timeout_;
    std::size_t bytesSent_ = 0;
};

/// Flat records (trivially copyable) as message bytes.
template <class T>
Bytes packRecords(std::span<const T> records) {
    static_assert(std::is_trivially_copyable_v<T>, "records travel as raw bytes");
    Bytes bytes(records.size_bytes());
    if (!bytes.empty()) std::memcpy(bytes.data(), records.data(), bytes.size());
    return bytes;
}

/// Records from message bytes sent by rank `from`. Throws RankError if the size is not a whole
/// number of records.
template <class T>
std::vector<T> unpackRecords(const Bytes& bytes, int from, std::string_view what) {
    static_assert(std::is_trivially_copyable_v<T>, "records travel as raw bytes");
    if (bytes.size() % sizeof(T) != 0)
        throw RankError(from, "rank " + std::to_string(from) + " sent " + std::to_string(bytes.size()) + " bytes for " +
                                  std::string(what) + ", not a whole number of " + std::to_string(sizeof(T)) + "-byte records");
    std::vector<T> records(bytes.size() / sizeof(T));
    if (!records.empty()) std::memcpy(records.data(), bytes.data(), bytes.size());
    return records;
}

}  // namespace throng::sim
