#include "gl/timestamp_log.h"

#include <algorithm>

#include "util/error.h"

namespace subdfit::gl {
namespace {

GlHandle<QueryTraits> timestampNow() {
    GLuint id = 0;
    glGenQueries(1, &id);
    glQueryCounter(id, GL_TIMESTAMP);
    return GlHandle<QueryTraits>(id);
}

}  // namespace

void TimestampLog::begin() {
    rounds_.emplace_back();
    rounds_.back().push_back({timestampNow(), ""});
}

void TimestampLog::mark(const char* phase) {
    SUBDFIT_CHECK(!rounds_.empty());
    rounds_.back().push_back({timestampNow(), phase});
}

std::vector<std::pair<std::string, std::vector<double>>> TimestampLog::collect() const {
    std::vector<std::pair<std::string, std::vector<double>>> phases;
    for (const auto& round : rounds_) {
        for (auto& [name, ms] : phases) ms.push_back(0.0);
        GLuint64 previous = 0;
        for (size_t k = 0; k < round.size(); ++k) {
            GLuint64 now = 0;
            glGetQueryObjectui64v(round[k].query.id(), GL_QUERY_RESULT, &now);
            if (k > 0) {
                auto it = std::find_if(phases.begin(), phases.end(), [&](const auto& p) { return p.first == round[k].phase; });
                if (it == phases.end()) {
                    phases.push_back({round[k].phase, std::vector<double>(size_t(&round - rounds_.data()) + 1, 0.0)});
                    it = phases.end() - 1;
                }
                it->second.back() += double(now - previous) * 1e-6;
            }
            previous = now;
        }
    }
    return phases;
}

}  // namespace subdfit::gl
