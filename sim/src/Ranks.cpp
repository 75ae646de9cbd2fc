#include "throng/sim/Ranks.h"

#include <climits>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <thread>

#ifdef THRONG_HAVE_MPI
#include <mpi.h>
#endif

namespace throng::sim {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kMaxTag = 9999;

void checkTag(int tag, std::string_view what) {
    if (tag < 0 || tag > kMaxTag)
        throw std::invalid_argument("Ranks: tag " + std::to_string(tag) + " of '" + std::string(what) + "' is outside 0.." +
                                    std::to_string(kMaxTag));
}

#ifdef THRONG_HAVE_MPI
std::string silentRank(int rank, std::chrono::milliseconds timeout, std::string_view what) {
    return "rank " + std::to_string(rank) + " did not take part in '" + std::string(what) + "' within " +
           std::to_string(timeout.count()) + " ms (it stopped, hangs or is behind)";
}

// Each message of a collective call travels with the tag of its call and kind (size, then payload).
int sizeTag(int tag) { return tag * 2; }
int payloadTag(int tag) { return tag * 2 + 1; }

// Requests in flight, each with the rank at its other end and whether it is a send.
struct Pending {
    std::vector<MPI_Request> requests;
    std::vector<int> peers;
    std::vector<char> sends;

    void add(MPI_Request r, int peer, bool send) { requests.push_back(r), peers.push_back(peer), sends.push_back(send); }
    void append(const Pending& other) {
        requests.insert(requests.end(), other.requests.begin(), other.requests.end());
        peers.insert(peers.end(), other.peers.begin(), other.peers.end());
        sends.insert(sends.end(), other.sends.begin(), other.sends.end());
    }

    // Waits until every request completes. Past the deadline, receives still open are cancelled
    // (nothing writes into their buffers afterwards) and RankError names the first rank missing.
    // Sends still open are left to MPI: their buffers must outlive the run, which a RankError ends
    // (the caller aborts), so the size headers they read are never freed on that path.
    void waitAll(Clock::time_point deadline, std::chrono::milliseconds timeout, std::string_view what) {
        int spins = 0;
        while (true) {
            int done = 0;
            MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
            if (done) {
                requests.clear(), peers.clear(), sends.clear();
                return;
            }
            if (Clock::now() > deadline) break;
            if (++spins > 64) std::this_thread::sleep_for(std::chrono::microseconds(50));
        }
        int missing = -1;
        for (std::size_t i = 0; i < requests.size(); ++i) {
            if (requests[i] == MPI_REQUEST_NULL) continue;
            int flag = 0;
            MPI_Test(&requests[i], &flag, MPI_STATUS_IGNORE);
            if (flag) continue;
            if (missing < 0) missing = peers[i];
            if (!sends[i]) {
                MPI_Cancel(&requests[i]);
                MPI_Wait(&requests[i], MPI_STATUS_IGNORE);
            }
        }
        requests.clear(), peers.clear(), sends.clear();
        throw RankError(missing, silentRank(missing, timeout, what));
    }
};

int messageCount(std::size_t bytes, int peer, std::string_view what) {
    if (bytes > static_cast<std::size_t>(INT_MAX))
        throw RankError(peer, "'" + std::string(what) + "': a message of " + std::to_string(bytes) + " bytes to or from rank " +
                                  std::to_string(peer) + " is larger than one MPI message holds");
    return static_cast<int>(bytes);
}

// Size headers of sends in flight: heap storage, kept until the process exits if a rank fails to
// take part, since MPI may still read it then.
struct Headers {
    std::unique_ptr<std::uint64_t[]> storage;
    std::uint64_t* values;
    explicit Headers(std::size_t n) : storage(new std::uint64_t[n]()), values(storage.get()) {}
    void abandon() {  // the run is ending: MPI keeps what it has not sent
        static std::mutex guard;
        static std::vector<std::unique_ptr<std::uint64_t[]>> kept;
        const std::lock_guard lock(guard);
        kept.push_back(std::move(storage));
    }
};

// One collective step for this rank: sends `payloads[k]` to rank `sendTo[k]` and receives one message
// from each rank of `receiveFrom` into `received` (indexed by rank), every message its size first,
// all within `deadline`. Throws RankError naming the first rank missing.
void transfer(std::span<const int> sendTo, std::span<const Bytes* const> payloads, std::span<const int> receiveFrom,
              std::vector<Bytes>& received, int tag, Clock::time_point deadline, std::chrono::milliseconds timeout,
              std::string_view what, std::size_t& bytesSent) {
    for (std::size_t k = 0; k < sendTo.size(); ++k) messageCount(payloads[k]->size(), sendTo[k], what);
    std::vector<std::uint64_t> sizesIn(receiveFrom.size(), 0);
    Pending heads, sends;
    for (std::size_t k = 0; k < receiveFrom.size(); ++k) {
        MPI_Request q;
        MPI_Irecv(&sizesIn[k], 1, MPI_UINT64_T, receiveFrom[k], sizeTag(tag), MPI_COMM_WORLD, &q);
        heads.add(q, receiveFrom[k], false);
    }
    Headers sizesOut(sendTo.size());
    for (std::size_t k = 0; k < sendTo.size(); ++k) {
        const Bytes& payload = *payloads[k];
        sizesOut.values[k] = payload.size();
        MPI_Request q;
        MPI_Isend(&sizesOut.values[k], 1, MPI_UINT64_T, sendTo[k], sizeTag(tag), MPI_COMM_WORLD, &q);
        sends.add(q, sendTo[k], true);
        if (!payload.empty()) {
            MPI_Isend(payload.data(), static_cast<int>(payload.size()), MPI_BYTE, sendTo[k], payloadTag(tag), MPI_COMM_WORLD, &q);
            sends.add(q, sendTo[k], true);
        }
        bytesSent += sizeof(std::uint64_t) + payload.size();
    }
    try {
        heads.waitAll(deadline, timeout, what);
        Pending bodies;
        for (std::size_t k = 0; k < receiveFrom.size(); ++k) {
            if (sizesIn[k] == 0) continue;
            Bytes& into = received[static_cast<std::size_t>(receiveFrom[k])];
            into.resize(sizesIn[k]);
            MPI_Request q;
            MPI_Irecv(into.data(), messageCount(into.size(), receiveFrom[k], what), MPI_BYTE, receiveFrom[k], payloadTag(tag),
                      MPI_COMM_WORLD, &q);
            bodies.add(q, receiveFrom[k], false);
        }
        bodies.append(sends);
        bodies.waitAll(deadline, timeout, what);
    } catch (const RankError&) {
        sizesOut.abandon();
        throw;
    }
}

void finaliseAtExit() {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (!finalised) MPI_Finalize();
}
#endif

}  // namespace

bool Ranks::mpiAvailable() {
#ifdef THRONG_HAVE_MPI
    return true;
#else
    return false;
#endif
}

bool Ranks::launchedByMpi() {
    // Open MPI's, PMIx's and Hydra's (MPICH) launchers each leave their mark in the environment.
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
        if (std::getenv(name)) return true;
    return false;
}

Ranks::Ranks(std::chrono::milliseconds timeout) : timeout_(timeout) {
    setTimeout(timeout);
#ifdef THRONG_HAVE_MPI
    if (!launchedByMpi()) return;
    static std::once_flag started;
    std::call_once(started, [] {
        int initialised = 0;
        MPI_Initialized(&initialised);
        if (initialised) return;
        int provided = 0;
        if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
            throw std::runtime_error("Ranks: MPI could not be started");
        if (provided < MPI_THREAD_SERIALIZED)
            throw std::runtime_error("Ranks: this MPI library cannot be called from more than one thread of a process");
        std::atexit(finaliseAtExit);
    });
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
#endif
}

void Ranks::setTimeout(std::chrono::milliseconds timeout) {
    if (timeout.count() <= 0) throw std::invalid_argument("Ranks: the timeout must be positive, not " + std::to_string(timeout.count()) + " ms");
    timeout_ = timeout;
}

std::vector<Bytes> Ranks::exchange(std::span<const Bytes> outgoing, int tag, std::string_view what) {
    checkTag(tag, what);
    if (outgoing.size() != static_cast<std::size_t>(size_))
        throw std::invalid_argument("Ranks::exchange: '" + std::string(what) + "' has " + std::to_string(outgoing.size()) +
                                    " outgoing messages for " + std::to_string(size_) + " ranks");
    std::vector<Bytes> incoming(static_cast<std::size_t>(size_));
    incoming[static_cast<std::size_t>(rank_)] = outgoing[static_cast<std::size_t>(rank_)];
#ifdef THRONG_HAVE_MPI
    if (size_ == 1) return incoming;
    std::vector<int> others;
    std::vector<const Bytes*> payloads;
    for (int r = 0; r < size_; ++r)
        if (r != rank_) others.push_back(r), payloads.push_back(&outgoing[static_cast<std::size_t>(r)]);
    transfer(others, payloads, others, incoming, tag, Clock::now() + timeout_, timeout_, what, bytesSent_);
#endif
    return incoming;
}

std::vector<Bytes> Ranks::gather(const Bytes& mine, int tag, std::string_view what) {
    checkTag(tag, what);
    if (size_ == 1) return {mine};
    std::vector<Bytes> all;
#ifdef THRONG_HAVE_MPI
    const Clock::time_point deadline = Clock::now() + timeout_;
    if (rank_ != 0) {
        const int root = 0;
        const Bytes* payload = &mine;
        transfer(std::span(&root, 1), std::span(&payload, 1), {}, all, tag, deadline, timeout_, what, bytesSent_);
        return all;
    }
    all.resize(static_cast<std::size_t>(size_));
    all[0] = mine;
    std::vector<int> others;
    for (int r = 1; r < size_; ++r) others.push_back(r);
    transfer({}, {}, others, all, tag, deadline, timeout_, what, bytesSent_);
#endif
    return all;
}

std::vector<Bytes> Ranks::allGather(const Bytes& mine, int tag, std::string_view what) {
    checkTag(tag, what);
    std::vector<Bytes> all(static_cast<std::size_t>(size_));
    all[static_cast<std::size_t>(rank_)] = mine;
#ifdef THRONG_HAVE_MPI
    if (size_ == 1) return all;
    std::vector<int> others;
    for (int r = 0; r < size_; ++r)
        if (r != rank_) others.push_back(r);
    const std::vector<const Bytes*> payloads(others.size(), &mine);
    transfer(others, payloads, others, all, tag, Clock::now() + timeout_, timeout_, what, bytesSent_);
#endif
    return all;
}

Bytes Ranks::broadcast(const Bytes& fromRoot, int tag, std::string_view what) {
    checkTag(tag, what);
    if (size_ == 1) return fromRoot;
    std::vector<Bytes> received(static_cast<std::size_t>(size_));
#ifdef THRONG_HAVE_MPI
    const Clock::time_point deadline = Clock::now() + timeout_;
    if (rank_ == 0) {
        std::vector<int> others;
        for (int r = 1; r < size_; ++r) others.push_back(r);
        const std::vector<const Bytes*> payloads(others.size(), &fromRoot);
        transfer(others, payloads, {}, received, tag, deadline, timeout_, what, bytesSent_);
        return fromRoot;
    }
    const int root = 0;
    transfer({}, {}, std::span(&root, 1), received, tag, deadline, timeout_, what, bytesSent_);
#endif
    return std::move(received[0]);
}

void Ranks::abort(int code) {
#ifdef THRONG_HAVE_MPI
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised) MPI_Abort(MPI_COMM_WORLD, code);
#endif
    std::exit(code);
}

}  // namespace throng::sim
