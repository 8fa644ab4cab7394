#pragma once
// Cages of several face counts (the budget search's ladder), built in order on threads of their
// own while the caller judges the ones already built: building a cage is CPU work, judging one
// is GL work, and each leaves the other core idle. On a machine of many cores several rungs are
// built at once: much of a rung (decimating the reference, OpenSubdiv's tables) runs on one core.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <future>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "mesh/polygon_mesh.h"
#include "simplify/cage/initial_cage.h"

namespace subdfit::simplify {

class CageLadder {
public:
    // Starts building at once; `reference` must outlive the ladder. `prepare` (if any) runs on
    // the builder's thread on each cage before it is handed over: CPU work its judge would
    // otherwise do between GL work (searchBudget's prepareToJudge).
    // `builders`: rungs built at once (0: by the machine's cores, one on up to 7).
    using Prepare = std::function<void(const mesh::PolygonMesh& cage)>;
    CageLadder(const mesh::PolygonMesh& reference, std::vector<int> faceCounts, CageShape shape = CageShape::Triangles,
               Prepare prepare = {}, unsigned builders = 0);
    ~CageLadder();  // stops the builder after the cage it is on, and waits for it
    CageLadder(const CageLadder&) = delete;
    CageLadder& operator=(const CageLadder&) = delete;

    size_t size() const { return cages_.size(); }
    CageShape shape() const { return shape_; }
    // The cage of faceCounts[k] (none where too few faces survive decimation), waiting for it;
    // rethrows what building it threw. Each k is taken once.
    std::optional<mesh::PolygonMesh> take(size_t k);
    // Where the ladder's cages came from, for cages of other counts once the ladder is built.
    const CageSource& source();

    // How many rungs may be built beyond those taken. The builder prepares each cage's
    // subdivision tables for its judge; built further ahead, they would push the tables of the
    // cage being judged out of their caches (subdiv/table_cache.h), to be built again.
    static constexpr size_t kRunAhead = 2;

private:
    void build(const mesh::PolygonMesh& reference, const std::vector<int>& faceCounts, const Prepare& prepare,
               unsigned builders);
    void buildRungs(const std::vector<int>& faceCounts, const Prepare& prepare);
    // Waits until rung k may be built (kRunAhead); false once building stops.
    bool mayBuild(size_t k);
    void releaseRunAhead();  // every rung may be built: the ladder is going, or is wanted whole

    CageShape shape_;
    std::vector<std::promise<std::optional<mesh::PolygonMesh>>> promises_;
    std::vector<std::future<std::optional<mesh::PolygonMesh>>> cages_;
    std::optional<CageSource> source_;
    std::vector<char> built_;  // promises_[k] was set (each k by the one thread that took it)
    std::atomic<size_t> next_{0};
    std::atomic<bool> stop_{false};
    std::mutex takenMutex_;
    std::condition_variable takenChanged_;
    size_t taken_ = 0;       // rungs below it taken (or passed over)
    bool runAhead_ = false;  // releaseRunAhead() was called
    std::thread builder_;
};

}  // namespace subdfit::simplify
