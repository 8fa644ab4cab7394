#pragma once
// One fit, step by step. `subdfit fit`, the stages of `simplify`, the viewer and the benchmarks
// all drive this, so the step, the resume rule, checkpoints and the report exist once.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "context/gl_context.h"
#include "codec/subd_format.h"
#include "fit/cage_fitter.h"
#include "fit/fit_report.h"
#include "fit/fit_scene.h"
#include "fit/step_schedule.h"

namespace subdfit::fit {

struct Progress {
    int step, steps;
    float loss;
    double seconds, etaSeconds;
};

struct FitHooks {
    std::function<void(const Progress&)> progress{};
    const std::atomic<bool>* cancel = nullptr;            // set: stop at the next step, checkpointed
    std::function<void(const std::string& line)> note{};  // news for the user, e.g. "nothing to resume"
    // A loss on views the caller trusts more than the single-sample monitor (simplify: its
    // choosing views, supersampled), of the fitter's current state: a second opinion on the
    // stage's best state (FitRun::kJudgeEvery).
    std::function<double()> judge{};
};

// Writes the maps `maps` has values for into the fitter's groups of the same kind (a group the
// fitter lacks, or values the maps lack, are left alone).
void writeMaps(CageFitter& fitter, const surface::SurfaceMaps& maps);

// Why a run of steps ended: its step count; the schedule found it converged; its probation
// found it could not improve on its start (FitRun::runTo); the user stopped it.
enum class StopReason { Reached, Converged, NoGain, Cancelled };
const char* toString(StopReason reason);

// The views a run's start and end are scored on for its report: the training views' scores
// cost a render of each, twice, and a caller that reads only the held-out ones can skip them.
enum class ReportScores { TrainingAndHoldout, HoldoutOnly };

// How the maps join a fit: data the plan hands the run. A run resumed past the join has the
// maps' θ from its checkpoint (no `startFrom`), but the settings are made again.
struct MapStage {
    // The maps they start from, made from the cage as fitted so far (a bake); empty: as they are.
    std::function<surface::SurfaceMaps(const mesh::PolygonMesh& cage)> startFrom{};
    bool freezeCage = false;           // the cage stays where it is from then on
    float geometricRate = 1.0f;        // a factor on the geometric maps' learning rates from then on
    float appearanceRate = 1.0f;       // and on the appearance maps'
    std::optional<float> noiseGate{};  // every map group's from then on, where set
};

class FitRun {
public:
    // Builds the fitter and scores the starting state (the report's "before"). Needs the
    // scene's GL context current; `programs` and `scene` must outlive the run.
    FitRun(const ResolvedFitOptions& options, gl::ProgramCache& programs, FitScene& scene,
           ReportScores scores = ReportScores::TrainingAndHoldout);

    // Continues from `checkpoint` if it exists: true when it did. Throws subdfit::Error naming
    // the file when it is damaged or was written for other inputs or settings.
    bool resume(const std::filesystem::path& checkpoint);

    // Sets the maps `maps` holds (baked elsewhere: simplify's bake) as the fit's start, before any
    // step: the groups it has values for take them, and the "before" scores are of them.
    void startFrom(const surface::SurfaceMaps& maps);
    void saveCheckpoint(const std::filesystem::path& checkpoint);

    int step() const { return fitter_->stepsTaken(); }
    bool done() const {
        return step() >= options_.steps || stopReason_ == StopReason::Converged || stopReason_ == StopReason::NoGain;
    }
    StopReason stopReason() const { return stopReason_; }

    // One step: its views, its perturbation samples, the update. With `measureLoss` the step also
    // sums the loss, for takeMeanLoss().
    void advance(bool measureLoss);
    float takeMeanLoss() { return fitter_->takeMeanLoss(); }

    // Steps until `until` (clamped to the planned steps), until the schedule says the stage has
    // converged (options.schedule "plateau"), until its probation says it cannot pay (its first
    // kProbation of the stage's steps, or kProbationMeasurements intervals of kProbationEvery
    // steps if fewer, brought no gain and make none likely: seconds spent for nothing), or until hooks.cancel:
    // progress about 50 times a run, a checkpoint every options.checkpointEvery steps and at the end.
    static constexpr double kProbation = 0.15;
    static constexpr int kProbationMeasurements = 5, kProbationEvery = 5;
    // Heights baked as they join pass a probation that stops only a clear rise (their loss can
    // lie flat before it falls), then this many times its steps later one that asks a gain: ten
    // untextured references, docs/measurements.md.
    static constexpr int kLateProbation = 4;
    // With hooks.judge, the monitor's best state is judged at the end of the stage's probation,
    // every kJudgeEvery steps of the stage after it (or from its start, in a stage without one)
    // and at the stage's end, and the stage keeps the judge's lowest: a probation whose best the
    // judge finds no better than the start stops the stage (no_gain), and so do kJudgedWorse
    // judgments in a row above the judge's lowest (converged).
    // The single-sample monitor can keep improving while the judge's loss rises: the glTF Duck's
    // atlas at 10 KB, its lowest 100 steps in and 12 % above it 800 steps later.
    static constexpr int kJudgeEvery = 100, kJudgedWorse = 2;
    // With hooks.judge, a stage past its probation whose monitored best is this many steps old
    // stops (converged): a refinement of a near-optimal start (simplify's bake) that stalls this
    // long gains nothing held out for its seconds (docs/measurements.md).
    static constexpr int kStalledSteps = 100;
    StopReason runTo(int until, const std::filesystem::path& checkpoint, const FitHooks& hooks = {});

    // The end of a stage: back to the best monitored parameters, if the last are not (so a fit
    // never ends worse than it started), and a fresh schedule for what follows: at the full step,
    // or with `keepStep` at the step this stage's halvings reached.
    void endStage(bool keepStep = false);

    // The whole fit in its stages: the cage alone until the maps' planned start (or until it has
    // converged), then with the maps as `maps` says, each stage ending at its best state.
    StopReason run(const std::filesystem::path& checkpoint, const FitHooks& hooks = {}, const MapStage& maps = {});

    // Scores the current state and writes cage.obj, the exports (fitted.glb, maps) and the
    // before / after / target PNGs of held-out view 0 into `out`, each atomically. report.json
    // is the caller's to write: toJson(report), plus what it adds.
    FitReport writeResults(const std::filesystem::path& out, const context::GlContext& context);

    // What writeResults codes into asset.subd, before coding (fit::shippableState), and as coded.
    codec::SubdAsset shippable();
    std::vector<unsigned char> coded();

    // How long the plateau schedule's windows grow (StepSchedule's `windowDoublings`).
    void setWindowDoublings(int doublings) { windowDoublings_ = doublings; }

    // Rebuilds the fitter at another tessellation level, keeping its state and hand-set rates.
    void setTessLevel(int level);

    const FitOptions& options() const { return options_; }
    FitOptions& options() { return options_; }
    FitScene& scene() { return scene_; }
    CageFitter& fitter() { return *fitter_; }
    gl::ProgramCache& programs() { return programs_; }

private:
    mesh::PolygonMesh fittedWorld() const;  // the cage as fitted, in world units
    // The schedule's step onto the fitter: the stage's for every group, times the cage's carried halvings for the vertices.
    void applyStep();

    FitOptions options_;
    gl::ProgramCache& programs_;
    FitScene& scene_;
    std::unique_ptr<CageFitter> fitter_;
    std::string fingerprint_;  // what a checkpoint must match
    int resumedFromStep_ = 0;
    ScheduleState schedule_;
    int bestStep_ = -1;  // of the last stage ended
    // The maps joining as `stage` says; `fresh`: not resumed past the join.
    void joinMaps(const MapStage& stage, bool fresh);
    bool mapsGiven_ = false;  // startFrom set the maps (a bake): their stage starts near its optimum
    void restoreBest();       // θ of every group back to the best monitored state
    void writeTheta(const std::vector<std::vector<float>>& theta);

    // What hooks.judge has seen of the stage under way. Not checkpointed: a resumed stage is
    // judged afresh, from the stage's start.
    struct Judged {
        int stageStart = -1;
        double loss = 0.0, monitorLoss = 0.0;  // of the judge's lowest state so far
        int step = -1;
        std::vector<std::vector<float>> theta{};
        int worseInARow = 0;  // judgments of the monitor's best since, none below it
        int lastJudged = -1;  // the step of the last judgment
    };
    Judged judged_;
    double judgeOf(const std::vector<std::vector<float>>& theta, const FitHooks& hooks);
    // Judges the monitor's best state (the stage's start first, on its first call in a stage):
    // how many judgments in a row have found none below the judge's lowest.
    int judgeTheBest(const FitHooks& hooks);
    void takeTheJudgedBest();                    // the judge's lowest as the stage's best, restored
    void endJudgedStage(const FitHooks& hooks);  // the stage's end, judged
    int probationSteps() const;                  // of the stage under way
    // The monitor views' loss now, recorded into `schedule`, and why the stage ends, if it does.
    std::optional<StopReason> monitor(StepSchedule& schedule, const FitHooks& hooks);
    // `rising`: a later probation ended early by a clear rise (StepSchedule::clearlyRose).
    std::optional<StopReason> endProbation(StepSchedule& schedule, const FitHooks& hooks, bool rising = false);
    StopReason stopReason_ = StopReason::Reached;
    int monitorEvery_;
    int windowDoublings_ = StepSchedule::kMostWindowDoublings;
    std::chrono::steady_clock::time_point started_;
    double fitSeconds_ = 0.0;
    double fitSecondsBefore_ = 0.0;  // a resumed run's steps before its resume, as last monitored
    std::vector<MonitorMeasurement> monitored_;
    void scoreStart();
    void scoreStartOnce();
    ReportScores scores_;
    bool startScored_ = false;
    std::optional<ViewSetScore> trainBefore_;
    HoldoutScore holdoutBefore_;
    std::vector<std::vector<float>> scoredTheta_;  // the θ those scores are of (empty: not to be reused)
};

}  // namespace subdfit::fit
