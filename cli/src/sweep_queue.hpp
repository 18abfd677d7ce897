// How a sweep's views are handed out: one process takes them all in order, a shard (--shard i/N,
// for job arrays without MPI) takes every N-th from i, and under mpirun the ranks share one work
// queue. The MPI queue is a pair of counters on rank 0 (next view, views finished) that every rank,
// rank 0 included, advances with an atomic MPI_Fetch_and_op in a passive-target window: no rank
// is a dispatcher, so all of them work, and a view goes to whichever rank is free first (views
// differ in cost by 10x and more, so a static split would wait for the slowest share).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

namespace lodopt::cli {

class ViewQueue {
public:
    virtual ~ViewQueue() = default;
    // The next view index to work on, or none when every view was handed out.
    virtual std::optional<std::size_t> next() = 0;
    // This process finished a view (or found it done); returns the views finished so far by all.
    virtual std::size_t finished() = 0;
    // Waits until every process has run out of views (a no-op without MPI).
    virtual void waitForAll() {}
    virtual int rank() const { return 0; }
    virtual int ranks() const { return 1; }
    // Whether this process writes the merged table (rank 0; a shard never does).
    virtual bool merges() const = 0;
};

// Every view in order, one process.
std::unique_ptr<ViewQueue> makeLocalQueue(std::size_t views);
// Views i, i + N, i + 2N, ... of `views` ("i/N", 0 <= i < N); throws UsageError on a bad spec.
std::unique_ptr<ViewQueue> makeShardQueue(std::size_t views, const std::string& spec);

// Whether this process was started by mpirun/mpiexec with more than one rank (the launcher's
// environment), whether or not this build has MPI.
bool launchedByMpi();
// Whether this build has Open MPI (LODOPT_WITH_MPI).
bool builtWithMpi();

// MPI_Init on construction, MPI_Finalize on destruction; abort() ends every rank with a code
// (a rank that fails cannot leave the others waiting at the end).
class MpiSession {
public:
    MpiSession();
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;
    int rank() const { return mRank; }
    int ranks() const { return mRanks; }
    [[noreturn]] void abort(int code);
    // The shared queue over `views` (collective: every rank calls it once).
    std::unique_ptr<ViewQueue> makeQueue(std::size_t views);
    // Every rank waits here (collective).
    void barrier();

private:
    int mRank = 0;
    int mRanks = 1;
};

}  // namespace lodopt::cli
