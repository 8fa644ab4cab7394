#include "subdiv/table_cache.h"

#include <list>
#include <mutex>

namespace subdfit::subdiv {
namespace {

// What the tables depend on.
struct TopologyKey {
    int isolationLevel = 0;
    int vertexCount = 0;
    std::vector<int> faceSizes, faceIndices;
    mesh::SubdivisionTags tags;
    friend bool operator==(const TopologyKey&, const TopologyKey&) = default;
};

TopologyKey keyOf(const mesh::PolygonMesh& mesh, int isolationLevel) {
    return {isolationLevel, mesh.vertexCount(), mesh.faceSizes, mesh.faceIndices, mesh.tags};
}

long pointsOf(const PatchSet& set) { return set.pointCount; }
long pointsOf(const AdaptiveTables& tables) { return tables.pointCount(); }

// Once the points the entries hold pass kMostPoints (an 8 000-face triangle cage's patch set
// holds about 850 000 at level 2, a few hundred MB), the smallest leave first, the newest never:
// they are the cheapest to build again, and a dense cage comes back late (settled, then fitted).
template <class Tables>
class TableCache {
public:
    template <class Build>
    std::shared_ptr<const Tables> get(const mesh::PolygonMesh& mesh, int isolationLevel, Build build) {
        TopologyKey key = keyOf(mesh, isolationLevel);
        {
            const std::lock_guard lock(mutex_);
            for (auto it = entries_.begin(); it != entries_.end(); ++it)
                if (it->key == key) {
                    entries_.splice(entries_.begin(), entries_, it);
                    return it->tables;
                }
        }
        // Built unlocked: another thread's cage need not wait for this one.
        auto tables = std::make_shared<const Tables>(build());
        const std::lock_guard lock(mutex_);
        entries_.push_front({std::move(key), tables});
        evictPast(kMostPoints);
        return tables;
    }

private:
    static constexpr long kMostPoints = 1'500'000;
    void evictPast(long most) {
        long points = 0;
        for (const Entry& e : entries_) points += pointsOf(*e.tables);
        while (points > most && entries_.size() > 1) {
            auto smallest = std::next(entries_.begin());
            for (auto it = smallest; it != entries_.end(); ++it)
                if (pointsOf(*it->tables) < pointsOf(*smallest->tables)) smallest = it;
            points -= pointsOf(*smallest->tables);
            entries_.erase(smallest);
        }
    }

    struct Entry {
        TopologyKey key;
        std::shared_ptr<const Tables> tables;
    };
    std::mutex mutex_;
    std::list<Entry> entries_;
};

}  // namespace

std::shared_ptr<const PatchSet> cachedPatchSet(const mesh::PolygonMesh& mesh, const PatchSetOptions& options) {
    static TableCache<PatchSet> cache;
    return cache.get(mesh, options.isolationLevel, [&] { return buildPatchSet(mesh, options); });
}

std::shared_ptr<const AdaptiveTables> cachedAdaptiveTables(const mesh::PolygonMesh& mesh, int isolationLevel) {
    static TableCache<AdaptiveTables> cache;
    return cache.get(mesh, isolationLevel, [&] { return buildAdaptiveTables(mesh, isolationLevel); });
}

}  // namespace subdfit::subdiv
