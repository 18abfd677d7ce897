#include "sweep_queue.hpp"

#include <cstdlib>
#include <stdexcept>

#include "cli_common.hpp"

#if defined(LODOPT_WITH_MPI)
#include <mpi.h>
#endif

namespace lodopt::cli {

namespace {

class LocalQueue final : public ViewQueue {
public:
    LocalQueue(std::size_t views, std::size_t first, std::size_t stride, bool merges)
        : mViews(views), mNext(first), mStride(stride), mMerges(merges) {}
    std::optional<std::size_t> next() override {
        if (mNext >= mViews) return std::nullopt;
        const std::size_t view = mNext;
        mNext += mStride;
        return view;
    }
    std::size_t finished() override { return ++mFinished; }
    bool merges() const override { return mMerges; }

private:
    std::size_t mViews, mNext, mStride;
    bool mMerges;
    std::size_t mFinished = 0;
};

}  // namespace

std::unique_ptr<ViewQueue> makeLocalQueue(std::size_t views) {
    return std::make_unique<LocalQueue>(views, 0, 1, true);
}

std::unique_ptr<ViewQueue> makeShardQueue(std::size_t views, const std::string& spec) {
    const std::size_t slash = spec.find('/');
    long index = -1, count = 0;
    try {
        if (slash == std::string::npos) throw std::invalid_argument(spec);
        std::size_t used = 0;
        index = std::stol(spec.substr(0, slash), &used);
        if (used != slash) throw std::invalid_argument(spec);
        count = std::stol(spec.substr(slash + 1), &used);
        if (used != spec.size() - slash - 1) throw std::invalid_argument(spec);
    } catch (const std::exception&) {
        throw UsageError("--shard '" + spec + "': expected i/N with 0 <= i < N (e.g. 3/16)");
    }
    if (count < 1 || index < 0 || index >= count) {
        throw UsageError("--shard '" + spec + "': expected i/N with 0 <= i < N (e.g. 3/16)");
    }
    return std::make_unique<LocalQueue>(views, std::size_t(index), std::size_t(count), false);
}

bool launchedByMpi() {
    // Open MPI's launcher sets OMPI_COMM_WORLD_SIZE; MPICH and Slurm's PMI set PMI_SIZE.
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
        const char* value = std::getenv(name);
        if (value && std::atoi(value) > 1) return true;
    }
    return false;
}

#if defined(LODOPT_WITH_MPI)

bool builtWithMpi() { return true; }

namespace {

class MpiQueue final : public ViewQueue {
public:
    MpiQueue(std::size_t views, int rank, int ranks) : mViews(views), mRank(rank), mRanks(ranks) {
        // Two counters on rank 0: the next view to hand out, and the views finished.
        const MPI_Aint bytes = rank == 0 ? MPI_Aint(2 * sizeof(long)) : 0;
        MPI_Win_allocate(bytes, sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &mCounters, &mWindow);
        if (rank == 0) {
            MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, mWindow);
            mCounters[0] = 0;
            mCounters[1] = 0;
            MPI_Win_unlock(0, mWindow);
        }
        MPI_Barrier(MPI_COMM_WORLD);
    }
    ~MpiQueue() override { MPI_Win_free(&mWindow); }
    std::optional<std::size_t> next() override {
        const long taken = add(0, 1);
        if (taken < 0 || std::size_t(taken) >= mViews) return std::nullopt;
        return std::size_t(taken);
    }
    std::size_t finished() override { return std::size_t(add(1, 1) + 1); }
    void waitForAll() override { MPI_Barrier(MPI_COMM_WORLD); }
    int rank() const override { return mRank; }
    int ranks() const override { return mRanks; }
    bool merges() const override { return mRank == 0; }

private:
    long add(int counter, long amount) {
        long before = 0;
        MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, mWindow);
        MPI_Fetch_and_op(&amount, &before, MPI_LONG, 0, counter, MPI_SUM, mWindow);
        MPI_Win_unlock(0, mWindow);
        return before;
    }
    std::size_t mViews;
    int mRank, mRanks;
    long* mCounters = nullptr;
    MPI_Win mWindow = MPI_WIN_NULL;
};

}  // namespace

MpiSession::MpiSession() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &mRank);
    MPI_Comm_size(MPI_COMM_WORLD, &mRanks);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

void MpiSession::abort(int code) {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);
}

std::unique_ptr<ViewQueue> MpiSession::makeQueue(std::size_t views) {
    return std::make_unique<MpiQueue>(views, mRank, mRanks);
}

void MpiSession::barrier() { MPI_Barrier(MPI_COMM_WORLD); }

#else

bool builtWithMpi() { return false; }

MpiSession::MpiSession() {
    throw UsageError("this lodopt was built without MPI (libopenmpi-dev): run it without mpirun, or use --shard");
}
MpiSession::~MpiSession() = default;
void MpiSession::abort(int code) { std::_Exit(code); }
std::unique_ptr<ViewQueue> MpiSession::makeQueue(std::size_t views) { return makeLocalQueue(views); }
void MpiSession::barrier() {}

#endif

}  // namespace lodopt::cli
