// The mode arbiter (paper Sec. III.A and III.D): holds the goal and the committed trajectory,
// starts planning rounds, picks the best verified answer, and keeps the vehicle on a continuous,
// safe trajectory (a stopping one at worst). The policy itself - when to replan, which modes to
// ask, when to stop - is in replan_rules.hpp; the fallback chain in fallback_chain.hpp; the check
// of an answer in answer_check.hpp. This class feeds them its state and carries out what they
// decide. No LCM here: the node feeds events in and publishes what comes out.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "mmh/arbiter/answer_check.hpp"
#include "mmh/arbiter/arbiter_params.hpp"
#include "mmh/arbiter/fallback_chain.hpp"
#include "mmh/arbiter/latency_monitor.hpp"
#include "mmh/arbiter/modes.hpp"
#include "mmh/arbiter/phase.hpp"
#include "mmh/arbiter/progress_monitor.hpp"
#include "mmh/arbiter/replan_rules.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/stopping_trajectory.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh::arbiter {

struct PlanRequestOut {
  int64_t request_id = 0;
  Mode mode = Mode::kNone;
  Trigger trigger = Trigger::kNone;
  int64_t start_utime = 0;     // the answer must start at this time...
  KinematicState start;        // ...in exactly this state
  int64_t deadline_utime = 0;  // answers after this are ignored
  double max_speed_mps = 0.0;  // the latency budget's speed limit (never below the start speed)
  int64_t map_seq = 0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Vector3d goal = Eigen::Vector3d::Zero();
  Trajectory reference;  // EAM on collision: rest of the committed trajectory from start_utime
};

struct ModeAnswer {
  int64_t request_id = 0;
  Mode mode = Mode::kNone;
  bool ok = false;
  int reason = 0;
  std::string detail;
  int64_t compute_us = 0;
  int64_t start_utime = 0;
  Trajectory trajectory;
};

struct CommitOut {
  int64_t trajectory_id = 0;
  int64_t start_utime = 0;
  Mode mode = Mode::kNone;
  Trajectory trajectory;
};

struct DecisionOut {
  int64_t decision_seq = 0;
  int64_t utime = 0;
  Trigger trigger = Trigger::kNone;
  Outcome outcome = Outcome::kFailed;
  bool awareness_safe = true;
  int8_t awareness_reason = 0;
  uint8_t modes_asked = 0;
  uint8_t modes_ok = 0;
  Mode committed_mode = Mode::kNone;
  int64_t request_id = 0;
  int64_t trajectory_id = 0;
  std::array<int64_t, 5> compute_us{};  // per Mode index
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d local_target = Eigen::Vector3d::Zero();
  std::string detail;
  // Committing or stopping in answer to a newly mapped danger (an obstacle or unmapped space on
  // the committed trajectory): the time of the map that first showed it (its scan's time). 0 else.
  int64_t threat_seen_utime = 0;
};

struct ArbiterCounters {
  std::array<int, 5> iterations{};  // answers received per Mode index (failed ones included)
  int decisions = 0;
  int commits = 0;
  int failures = 0;          // decisions without a usable answer
  int unanswered = 0;        // requests that got no answer by their deadline
  int late_answers = 0;      // answers after the decision was taken
  int rejected_answers = 0;  // OK answers that failed the arbiter's own checks
  int stops = 0;             // stopping trajectories committed
  int rejected_goals = 0;
  int stale_odometry = 0;            // times ODOMETRY went stale (no planning until it returns)
  int not_committed_stale_odom = 0;  // verified answers dropped because ODOMETRY was stale
  int unreachable_goals = 0;         // times a goal was given up for lack of progress
  int back_offs = 0;                 // rounds that backed off to free space while stuck
  int slowdowns = 0;  // committed trajectories slowed to the latency budget's speed limit
  int failed_round_slowdowns = 0;  // ... slowed because every mode failed with danger ahead
  int swerving_stops = 0;     // stops under way replaced by one that swerves round a new obstacle
  int last_resort_stops = 0;  // ... by one not clear, but off the cells the first would touch
  int backup_stops = 0;       // failed rounds answered by flying on with a verified backup stop
  int retraces = 0;  // back-offs flown along the way the vehicle came, when no mode answered
  int degraded_periods = 0;  // times the latency budget became degraded
  int moved_goals = 0;       // goals moved out of an obstacle's margin
  int kept_trajectories =
      0;  // halfway answers not taken: the committed one reaches the goal sooner
};

class Arbiter {
 public:
  explicit Arbiter(const ArbiterParams& params);

  // --- inputs -----------------------------------------------------------------------------
  // A new goal (or a moved one). Refused (false, with the reason) when outside the geofence or
  // inside a mapped obstacle's margin with no free point within goal_relocate_radius_m; moved to
  // the nearest free point when there is one (a kGoalMoved decision says where).
  bool setGoal(int64_t goal_id, const Eigen::Vector3d& goal, int64_t now, std::string* why);
  void setAwareness(bool safe, int8_t reason, int64_t goal_id, int64_t map_seq);
  // The grid must stay alive until the next call (the node owns it).
  void onMapUpdated(const VoxelGrid& grid, int64_t map_seq, int64_t map_utime, int64_t now);
  void onOdometry(const KinematicState& state, int64_t now);
  void onAnswer(const ModeAnswer& answer, int64_t now);
  // Time passed without any input (a real-time node's idle tick): what depends on the clock
  // alone - stale ODOMETRY, a round's deadline - is decided at `now`.
  void onClock(int64_t now);

  // --- outputs (the node takes them after every input) -----------------------------------
  std::vector<PlanRequestOut> takeRequests() { return std::exchange(requests_, {}); }
  std::optional<CommitOut> takeCommit() { return std::exchange(commit_, std::nullopt); }
  std::vector<DecisionOut> takeDecisions() { return std::exchange(decisions_, {}); }

  // --- state --------------------------------------------------------------------------------
  const ArbiterCounters& counters() const { return counters_; }
  const ArbiterParams& params() const { return params_; }
  Phase phase() const { return phase_; }
  bool hasGoal() const { return phase_ != Phase::kIdle; }
  bool hasCommitted() const { return !committed_.trajectory.empty(); }
  // What the vehicle was sent to fly (with its backup stop, if any).
  const Trajectory& committed() const { return flownTrajectory(); }
  int64_t committedStartUtime() const { return committed_.start_utime; }
  Mode committedMode() const { return committed_.mode; }
  bool pending() const { return round_.has_value(); }  // a planning round is in flight
  bool reached() const { return phase_ == Phase::kReached; }
  bool mapStale(int64_t now) const;
  int64_t now() const { return now_; }  // newest time seen (inputs and onClock)
  // The replan lead and answer deadline in use, and whether (and why) the computer is too slow
  // for the configured ones (replan_rules.hpp, latencyBudget).
  const LatencyBudget& latencyBudget() const { return budget_; }
  // ODOMETRY received before, but older than stale_odometry_s at `now` (message clock).
  bool odometryStale(int64_t now) const;

 private:
  struct Goal {
    int64_t id = 0;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();   // where the vehicle flies to
    Eigen::Vector3d requested = Eigen::Vector3d::Zero();  // as the GOAL message gave it
  };
  struct Awareness {
    bool safe = true;
    int8_t reason = 0;
    int64_t goal_id = -1;
  };
  struct Committed {
    Trajectory trajectory;
    int64_t start_utime = 0;
    Mode mode = Mode::kNone;
    bool ends_at_goal = false;
    // A repair of the plan before it (replan_rules.hpp, replanPointS): that plan's replan point.
    std::optional<int64_t> repaired_replan_utime;
    // Kept over a later halfway answer (replan_rules.hpp, keepsCommitted): its next replan point.
    std::optional<int64_t> kept_replan_utime;
    double bound_s = 0.0;  // restToRestTime of its straight length
    // Started inside the check margin: the escape accepted at commit lasts until escape_until_s
    // and must keep escape_min_distance_m from the occupied cells (answer_check.hpp).
    double escape_until_s = 0.0;
    double escape_min_distance_m = 0.0;
    // Flown on after every mode failed (flyOnWithBackupStop): `trajectory` is the path the
    // arbiter checks and asks about, `backup` what the vehicle flies, the same path up to
    // backup_stop_s and then a stop clear of the danger. Once the vehicle brakes on it, the backup
    // becomes the committed stop.
    std::optional<Trajectory> backup;
    double backup_stop_s = 0.0;
    // The arbiter's own way back along the flown path (retraceOutOfTheSpot): watched only for
    // occupied cells nearer than escape_min_distance_m (the nearest it was found to come), as it
    // runs inside the planners' margin where the vehicle has flown.
    bool retrace = false;
  };
  // A planning round in flight: requests sent, answers collected until all came or the deadline.
  struct Round {
    Trigger trigger = Trigger::kNone;
    RequestedStart start;
    int64_t deadline_utime = 0;
    Eigen::Vector3d target = Eigen::Vector3d::Zero();
    bool target_is_goal = false;
    std::vector<PlanRequestOut> requests;
    std::vector<ModeAnswer> answers;
    std::string note;        // why this round has an unusual target (a back-off)
    bool repairs = false;    // re-plans the rest of the committed trajectory, to its end
    bool backs_off = false;  // the stuck detector's back-off (target: recently flown free space)
    std::optional<int64_t> threat_seen_utime;  // the danger this round answers, if any
  };

  // The policy's inputs now (replan_rules.hpp).
  ReplanView replanView(int64_t now) const;
  // What the stop rule for `cause` reads (shouldStop).
  StopView stopView(int64_t now, StopCause cause) const;

  void evaluate(int64_t now);
  // When a trajectory decided at `now` takes over: after the replan lead, and never before the
  // committed trajectory's own start.
  int64_t takeOverUtime(int64_t now) const;
  // The latency budget lowered the speed limit below the committed trajectory's speed: commit
  // that trajectory slowed down along its path (when the slowed one is collision-free), also
  // while a round is in flight (whose answer, if committed, starts before the slowdown).
  void slowDownIfTooFast(int64_t now);
  // A new map put the goal into an obstacle's margin: move it to the nearest free point.
  void relocateGoalIfBlocked();
  void reportGoalMoved(const std::string& why);
  // back_off: the target of a stuck retry (recently flown free space), else the usual target.
  void startRound(Trigger trigger, const std::vector<Mode>& modes, int64_t now,
                  const std::optional<Eigen::Vector3d>& back_off);
  // No progress for give_up_s: hold (a stop if moving) and report the goal unreachable.
  void giveUp(int64_t now);
  void decide(int64_t now, bool by_deadline);
  // `repairs`: the trajectory re-plans the committed one's rest to the same end (it keeps that
  // plan's replan point).
  void commit(const Trajectory& trajectory, int64_t start_utime, Mode mode, bool ends_at_goal,
              bool repairs = false);
  // When rule (1) replans the committed trajectory (replanPointS), on the message clock.
  int64_t committedReplanUtime() const;
  std::optional<double> repairedReplanPointS() const;
  std::optional<double> keptReplanPointS() const;
  // Commits a stopping trajectory (the one given, else stopAlongCommitted from the replan lead);
  // every caller has asked shouldStop() first.
  void commitStop(int64_t now, const std::string& why, Trigger trigger,
                  const Trajectory* stop = nullptr);
  // The stop under way meets a newly mapped obstacle and every mode failed: commit a stop from
  // the replan lead that is clear of it (one that swerves, chooseStoppingTrajectory), if any; or,
  // when the stop under way would bring the airframe into an occupied cell, the chosen one if it
  // does not.
  void swerveIfStopMeetsObstacle(int64_t now, const std::string& notes, Trigger trigger);
  void onStaleOdometry(int64_t now);
  // After a failed round, and while recovering: commits the stop for the danger ahead once it
  // cannot wait any longer (shouldStop, StopCause::kNoUsableAnswer).
  // The decision's detail names the danger, then `notes` (what the modes said). True when danger
  // is ahead and the stop can still wait.
  bool stopIfNoTimeLeft(int64_t now, bool by_deadline, const std::string& notes, Trigger trigger);
  // Every mode failed with danger ahead and the stop can wait: fly on along the committed path,
  // slowed to failed_round_speed_ratio of its speed (if that meets nothing sooner), and commit it
  // up to the latest point from which braking along it still ends clear of the known obstacles in
  // known space, less stop_decision_margin_s, followed by that stop (the backup stop). A mode's
  // answer on a later map replaces it; else the vehicle brakes there (a kStopping decision).
  // Without such a point, the slowed path alone.
  void flyOnWithBackupStop(int64_t now, Trigger trigger);
  // A back-off round in which no mode answered: back to the back-off point along the positions
  // flown since (ProgressMonitor::backOffRoute), slowly (retrace_speed_mps), from rest, when that
  // keeps the airframe off every occupied cell, and not once the goal is given up. The modes plan
  // again from there. False when nothing was committed.
  bool retraceOutOfTheSpot(const Round& round, DecisionOut& d);
  // The path up to tb, then the stop braking along it from there.
  Trajectory backupAlong(const Trajectory& path, double tb) const;
  // The latest tb within horizon_s from which braking along `path` is clear (isClearStop: the
  // known obstacles, known space, the geofence), by bisection; then margin_s earlier, where the
  // whole backup (backupAlong) must be clear. Nothing when braking at once is not clear.
  std::optional<double> latestBackupStopS(const Trajectory& path, double horizon_s,
                                          double margin_s) const;
  // The committed trajectory is flown as backupAlong(it, backup_stop_s) (the commit just made).
  void setBackup(double backup_stop_s);
  // The vehicle has reached the backup stop of the committed trajectory: report the stop.
  void reportBrakingOnBackupStop(int64_t now);
  // A stop begun stop_decision_margin_s later would still end clear of the known obstacles.
  bool stopCanWait(int64_t now) const;
  // The stop (chooseStoppingTrajectory) that leaves the committed trajectory t0_s into it; one
  // that swerves only if may_swerve.
  Trajectory stopAlongCommitted(double t0_s, bool may_swerve = true) const;
  // The arbiter's further condition on a clear stop (isClearStop): the airframe meets no mapped
  // obstacle's unseen side beside it (touchesHiddenFace); empty with hidden_face_m 0.
  StopCondition noHiddenFaceBeside() const;
  // Sets the phase after a round's decision or a stop, unless a new goal came meanwhile (its
  // round comes next whatever the old round decided).
  void enterPhase(Phase phase);
  bool collisionAhead(int64_t now) const;
  // First time in [from_s, to_s] at which the committed trajectory collides with the map; its
  // accepted escape from a start in the margin only when it enters an occupied cell or comes
  // nearer to the occupied cells than the start did. Else a repair round would be asked for the
  // escape itself, fail from the margin, and stop the vehicle there round after round.
  std::optional<double> committedCollisionTime(double from_s, double to_s) const;
  // Nearer than this to an occupied cell's centre, the airframe enters the cell.
  double stopTouchDistance() const;
  // A collision ahead that needs a round now (collisionNeedsRoundNow); *eta_s until it is hit.
  bool collisionThreat(int64_t now, double* eta_s) const;
  // Seconds until the committed trajectory enters unmapped space within the vehicle's reach
  // (firstUnknownWithinReach) if the stop began extra_s after the current replan lead; nothing
  // when the reach is mapped, or the committed trajectory is a stop (chosen as the safest).
  // `where`, if given, receives the unknown cell.
  std::optional<double> unmappedAhead(int64_t now, double extra_s,
                                      UnmappedCell* where = nullptr) const;
  // Whether a danger on the committed trajectory lies on what the vehicle flies: with a backup
  // stop, only an obstacle on the backup or unmapped space within its reach counts; one beyond
  // the backup stop is answered already (the vehicle stops before it unless a mode answers).
  bool dangerOnFlownTrajectory(int64_t now) const;
  // How long the vehicle has been at rest with no mode's answer committed (0: moving).
  double stillUnansweredS(int64_t now) const;
  // The stuck detector's response now (stuckResponse of the progress and the at-rest clocks).
  StuckResponse stuckNow(int64_t now) const;
  KinematicState stateAt(int64_t utime) const;
  // What the vehicle flies: the committed trajectory, or its backup (Committed::backup).
  const Trajectory& flownTrajectory() const;
  Geofence geofence() const { return Geofence{params_.geofence_min_m, params_.geofence_max_m}; }
  // The box the arbiter's own trajectory from `start` keeps to (fenceForStart): a vehicle left
  // just outside the fence by an accepted answer still has stops and a way back.
  Geofence fenceFrom(const Eigen::Vector3d& start) const;
  Eigen::Vector3d vehiclePosition() const;
  void pushDecision(DecisionOut decision);
  void updateLatencyBudget();

  ArbiterParams params_;
  Phase phase_ = Phase::kIdle;
  Goal goal_;
  // Inputs.
  int64_t now_ = 0;  // newest message-clock time seen
  std::optional<KinematicState> odometry_;
  int64_t odometry_utime_ = 0;
  std::optional<Awareness> awareness_;
  const VoxelGrid* grid_ = nullptr;
  int64_t map_seq_ = 0, map_utime_ = 0;
  // Stops already committed for a stale input (one per stale period).
  bool stopped_for_stale_map_ = false;
  bool stopped_for_stale_odometry_ = false;
  // Committed trajectory and planning.
  Committed committed_;
  std::optional<Round> round_;
  std::optional<double> collision_eta_s_;     // a threatening collision awaits its round
  std::string threat_note_;                   // what the threat is, when not an obstacle
  std::optional<int64_t> threat_seen_utime_;  // map time of the danger not yet answered
  FallbackChain chain_;
  ProgressMonitor progress_;
  LatencyMonitor latency_;
  LatencyBudget budget_;
  std::optional<int64_t> last_backoff_utime_;
  std::optional<int64_t> still_since_utime_;  // the vehicle has been at rest since then
  int64_t last_answer_utime_ = 0;             // a mode's answer (or a retrace) was last committed
  std::string last_failure_notes_;  // of the newest failed round, for the unreachable report
  int64_t last_round_utime_ = 0;
  Eigen::Vector3d last_round_position_ = Eigen::Vector3d::Zero();
  int64_t next_trajectory_id_ = 1;
  int64_t next_request_id_ = 1;
  int64_t next_decision_seq_ = 1;
  // Outputs.
  std::vector<PlanRequestOut> requests_;
  std::optional<CommitOut> commit_;
  std::vector<DecisionOut> decisions_;
  ArbiterCounters counters_;
};

}  // namespace mmh::arbiter
