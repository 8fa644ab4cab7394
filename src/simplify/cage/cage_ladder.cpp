#include "simplify/cage/cage_ladder.h"

#include "util/error.h"
#include "util/interrupt.h"

namespace subdfit::simplify {

CageLadder::CageLadder(const mesh::PolygonMesh& reference, std::vector<int> faceCounts, Prepare prepare)
    : promises_(faceCounts.size()) {
    for (auto& promise : promises_) cages_.push_back(promise.get_future());
    builder_ = std::thread([this, &reference, counts = std::move(faceCounts), prepare = std::move(prepare)] {
        build(reference, counts, prepare);
    });
}

CageLadder::~CageLadder() {
    stop_ = true;
    if (builder_.joinable()) builder_.join();
}

void CageLadder::build(const mesh::PolygonMesh& reference, const std::vector<int>& faceCounts, const Prepare& prepare) {
    size_t k = 0;
    try {
        source_.emplace(reference);
        for (; k < faceCounts.size() && !stop_; ++k) {
            try {
                mesh::PolygonMesh cage = source_->cage({.faces = faceCounts[k]});
                if (prepare) prepare(cage);
                promises_[k].set_value(std::move(cage));
            } catch (const Interrupted&) {
                throw;
            } catch (const Error&) {
                promises_[k].set_value(std::nullopt);  // too few faces survive: the caller goes on
            }
        }
    } catch (...) {
        // The source failed, or building was interrupted: the cage waited for reports it.
        if (k < promises_.size()) promises_[k].set_exception(std::current_exception());
    }
}

std::optional<mesh::PolygonMesh> CageLadder::take(size_t k) { return cages_.at(k).get(); }

const CageSource& CageLadder::source() {
    if (builder_.joinable()) builder_.join();
    if (!source_) throw Error("the cage ladder has no source: preparing the reference failed");
    return *source_;
}

}  // namespace subdfit::simplify
