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

std::string silentRank(int rank, std::chrono::milliseconds timeout, std::string_view what) {
    return "rank " + std::to_string(rank) + " did not take part in '" + std::string(what) + "' within " +
           std::to_string(timeout.count()) + " ms (it stopped, hangs or is behind)";
}

#ifdef THRONG_HAVE_MPI
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
        if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
            throw std::runtime_error("Ranks: MPI could not be started");
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
    for (int r = 0; r < size_; ++r) messageCount(outgoing[static_cast<std::size_t>(r)].size(), r, what);
    const Clock::time_point deadline = Clock::now() + timeout_;
    Headers sendSizes(incoming.size());
    std::vector<std::uint64_t> recvSizes(incoming.size(), 0);
    Pending sizes, sends;
    for (int r = 0; r < size_; ++r) {
        if (r == rank_) continue;
        const auto i = static_cast<std::size_t>(r);
        sendSizes.values[i] = outgoing[i].size();
        MPI_Request q;
        MPI_Irecv(&recvSizes[i], 1, MPI_UINT64_T, r, sizeTag(tag), MPI_COMM_WORLD, &q);
        sizes.add(q, r, false);
        MPI_Isend(&sendSizes.values[i], 1, MPI_UINT64_T, r, sizeTag(tag), MPI_COMM_WORLD, &q);
        sends.add(q, r, true);
        bytesSent_ += sizeof(std::uint64_t);
        if (!outgoing[i].empty()) {
            MPI_Isend(outgoing[i].data(), messageCount(outgoing[i].size(), r, what), MPI_BYTE, r, payloadTag(tag), MPI_COMM_WORLD, &q);
            sends.add(q, r, true);
            bytesSent_ += outgoing[i].size();
        }
    }
    try {
        sizes.waitAll(deadline, timeout_, what);
        Pending payloads;
        for (int r = 0; r < size_; ++r) {
            const auto i = static_cast<std::size_t>(r);
            if (r == rank_ || recvSizes[i] == 0) continue;
            incoming[i].resize(recvSizes[i]);
            MPI_Request q;
            MPI_Irecv(incoming[i].data(), messageCount(incoming[i].size(), r, what), MPI_BYTE, r, payloadTag(tag), MPI_COMM_WORLD, &q);
            payloads.add(q, r, false);
        }
        payloads.append(sends);
        payloads.waitAll(deadline, timeout_, what);
    } catch (const RankError&) {
        sendSizes.abandon();
        throw;
    }
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
        Headers size(1);
        size.values[0] = mine.size();
        Pending sends;
        MPI_Request q;
        MPI_Isend(size.values, 1, MPI_UINT64_T, 0, sizeTag(tag), MPI_COMM_WORLD, &q);
        sends.add(q, 0, true);
        if (!mine.empty()) {
            MPI_Isend(mine.data(), messageCount(mine.size(), 0, what), MPI_BYTE, 0, payloadTag(tag), MPI_COMM_WORLD, &q);
            sends.add(q, 0, true);
        }
        bytesSent_ += sizeof(std::uint64_t) + mine.size();
        try {
            sends.waitAll(deadline, timeout_, what);
        } catch (const RankError&) {
            size.abandon();
            throw;
        }
        return all;
    }
    all.resize(static_cast<std::size_t>(size_));
    all[0] = mine;
    std::vector<std::uint64_t> sizes(all.size(), 0);
    Pending heads;
    for (int r = 1; r < size_; ++r) {
        MPI_Request q;
        MPI_Irecv(&sizes[static_cast<std::size_t>(r)], 1, MPI_UINT64_T, r, sizeTag(tag), MPI_COMM_WORLD, &q);
        heads.add(q, r, false);
    }
    heads.waitAll(deadline, timeout_, what);
    Pending payloads;
    for (int r = 1; r < size_; ++r) {
        const auto i = static_cast<std::size_t>(r);
        if (sizes[i] == 0) continue;
        all[i].resize(sizes[i]);
        MPI_Request q;
        MPI_Irecv(all[i].data(), messageCount(all[i].size(), r, what), MPI_BYTE, r, payloadTag(tag), MPI_COMM_WORLD, &q);
        payloads.add(q, r, false);
    }
    payloads.waitAll(deadline, timeout_, what);
#endif
    return all;
}

Bytes Ranks::broadcast(const Bytes& fromRoot, int tag, std::string_view what) {
    checkTag(tag, what);
    if (size_ == 1) return fromRoot;
    Bytes result;
#ifdef THRONG_HAVE_MPI
    const Clock::time_point deadline = Clock::now() + timeout_;
    if (rank_ == 0) {
        messageCount(fromRoot.size(), 1, what);
        Headers size(1);
        size.values[0] = fromRoot.size();
        Pending sends;
        for (int r = 1; r < size_; ++r) {
            MPI_Request q;
            MPI_Isend(size.values, 1, MPI_UINT64_T, r, sizeTag(tag), MPI_COMM_WORLD, &q);
            sends.add(q, r, true);
            if (!fromRoot.empty()) {
                MPI_Isend(fromRoot.data(), static_cast<int>(fromRoot.size()), MPI_BYTE, r, payloadTag(tag), MPI_COMM_WORLD, &q);
                sends.add(q, r, true);
            }
            bytesSent_ += sizeof(std::uint64_t) + fromRoot.size();
        }
        try {
            sends.waitAll(deadline, timeout_, what);
        } catch (const RankError&) {
            size.abandon();
            throw;
        }
        return fromRoot;
    }
    std::uint64_t size = 0;
    Pending head;
    MPI_Request q;
    MPI_Irecv(&size, 1, MPI_UINT64_T, 0, sizeTag(tag), MPI_COMM_WORLD, &q);
    head.add(q, 0, false);
    head.waitAll(deadline, timeout_, what);
    result.resize(size);
    if (size > 0) {
        Pending payload;
        MPI_Irecv(result.data(), messageCount(result.size(), 0, what), MPI_BYTE, 0, payloadTag(tag), MPI_COMM_WORLD, &q);
        payload.add(q, 0, false);
        payload.waitAll(deadline, timeout_, what);
    }
#endif
    return result;
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
