#pragma once
// Tables of the few cages built last, kept by topology (faces, vertex count, tags and level;
// positions play no part in them): simplify draws one cage with several maps, bakes onto it,
// settles it and fits it, each time through a CageFitter or LimitEvaluator of its own, and on a
// dense cage building the tables again costs as much as several renders. One cache per kind of
// table (cachedPatchSet, cachedAdaptiveTables); thread-safe; what it hands out stays valid after
// it leaves the cache.
#include <functional>
#include <iterator>
#include <list>
#include <memory>
#include <mutex>
#include <vector>

#include "mesh/polygon_mesh.h"

namespace subdfit::subdiv {

// What a cage's tables depend on.
struct TopologyKey {
    int isolationLevel = 0;
    int vertexCount = 0;
    std::vector<int> faceSizes, faceIndices;
    mesh::SubdivisionTags tags;
    friend bool operator==(const TopologyKey&, const TopologyKey&) = default;
};

// Entries are weighed in points (`pointsOf`). Once they pass `mostPoints` (a 5 000-face
// triangle cage's tables hold about half a million; their sizes in docs/measurements.md), the
// least recently used leave first: simplify's search comes back to the light cages of its map ladders again and
// again, while a dense cage, drawn at a shallow level, builds again in a fraction of a second.
template <class Tables>
class TableCache {
public:
    TableCache(long mostPoints, std::function<long(const Tables&)> pointsOf)
        : mostPoints_(mostPoints), pointsOf_(std::move(pointsOf)) {}

    // The tables kept for `mesh`'s topology at `isolationLevel`, or `build()`'s (then kept).
    template <class Build>
    std::shared_ptr<const Tables> get(const mesh::PolygonMesh& mesh, int isolationLevel, Build build) {
        TopologyKey key{isolationLevel, mesh.vertexCount(), mesh.faceSizes, mesh.faceIndices, mesh.tags};
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
        evictPastMost();
        return tables;
    }

private:
    struct Entry {
        TopologyKey key;
        std::shared_ptr<const Tables> tables;
    };

    void evictPastMost() {
        long points = 0;
        for (const Entry& e : entries_) points += pointsOf_(*e.tables);
        while (points > mostPoints_ && entries_.size() > 1) {
            points -= pointsOf_(*entries_.back().tables);
            entries_.pop_back();
        }
    }

    long mostPoints_;
    std::function<long(const Tables&)> pointsOf_;
    std::mutex mutex_;
    std::list<Entry> entries_;
};

// How many points each cache may hold: the budget search's cage being judged, in both its
// topologies (as built and as decoded), and the next rungs its builder prepares (CageLadder's
// kRunAhead) fit in it on the README demo (docs/measurements.md).
inline constexpr long kMostCachedPoints = 2'500'000;

}  // namespace subdfit::subdiv
