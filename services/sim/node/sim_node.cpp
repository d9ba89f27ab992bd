#include "sim_node.hpp"

#include <sstream>

#include "mmh/common/msg_convert.hpp"

namespace mmh {

SimNode::SimNode(ServiceContext& ctx, const Config& config, const SimOptions& options)
    : ctx_(ctx), sim_(sim::loadSimParams(config), options) {
  ctx_.clock().observe(sim_.nowUtime());
  const sim::MissionMetrics& m = sim_.metrics();
  std::ostringstream out;
  out << ctx_.service() << ": " << sim_.world().describe() << ", start (" << options.start.x()
      << ", " << options.start.y() << ", " << options.start.z() << "), goal (" << options.goal.x()
      << ", " << options.goal.y() << ", " << options.goal.z() << "), shortest path "
      << m.shortest_path_m << " m, time bound " << m.time_bound_s << " s, sensor "
      << options.sensor;
  logInfo(out.str());
  if (sim_.followsSetpoints()) {
    ctx_.subscribe(channels::kSetpoint, &SimNode::onSetpoint, this);
  } else {
    ctx_.subscribe(channels::kTrajectory, &SimNode::onTrajectory, this);
  }
  ctx_.subscribe(channels::kGoal, &SimNode::onGoal, this);
  ctx_.subscribe(channels::kArbiterStatus, &SimNode::onArbiterStatus, this);
}

void SimNode::onArbiterStatus(const arbiter_status_t& msg) {
  if (msg.outcome != arbiter_status_t::OUTCOME_GOAL_MOVED) return;
  // The detail names the goal ("goal 3: ..."): a move of an older goal is not this one's.
  const std::string prefix = "goal " + std::to_string(sim_.metrics().goal_id) + ":";
  if (msg.detail.compare(0, prefix.size(), prefix) != 0) return;
  const Eigen::Vector3d moved = toVec3(msg.local_target);
  if (sim_.acceptMovedGoal(moved)) {
    logInfo(ctx_.service() + ": arrival measured at the moved goal (" + std::to_string(moved.x()) +
            ", " + std::to_string(moved.y()) + ", " + std::to_string(moved.z()) + ")");
  } else {
    logWarn(ctx_.service() +
            ": the arbiter moved the goal beyond arbiter.goal_relocate_radius_m; "
            "arrival is still measured at the goal sent");
  }
}

void SimNode::onTrajectory(const trajectory_t& msg) {
  auto trajectory = std::make_shared<const Trajectory>(fromMsg(msg));
  if (!trajectory->empty() && !trajectory->isFinite()) {
    ctx_.reject("rejected_trajectory", "TRAJECTORY " + std::to_string(msg.trajectory_id) +
                                           " has non-finite or non-positive pieces");
    return;
  }
  if (msg.start_utime < sim_.nowUtime()) {
    // Late: it takes over at the next step, partway through.
    ctx_.increment("trajectory_late");
  }
  sim_.commitTrajectory(std::move(trajectory), msg.start_utime, msg.trajectory_id);
  ctx_.increment("trajectories_received");
}

void SimNode::onGoal(const goal_t& msg) {
  if (msg.goal_id != sim_.metrics().goal_id) {
    logInfo(ctx_.service() + ": goal " + std::to_string(msg.goal_id) + " at (" +
            std::to_string(msg.position[0]) + ", " + std::to_string(msg.position[1]) + ", " +
            std::to_string(msg.position[2]) + ")");
  }
  sim::MissionGoal goal;
  goal.position = toVec3(msg.position);
  goal.goal_id = msg.goal_id;
  goal.waypoint_index = msg.waypoint_index;
  goal.num_waypoints = msg.num_waypoints;
  goal.tolerance_m = msg.tolerance_m;
  goal.stop = msg.stop;
  sim_.setMissionGoal(goal);
}

void SimNode::onSetpoint(const setpoint_t& msg) {
  sim::SetpointSample s;
  s.utime = msg.header.utime;
  s.trajectory_id = msg.trajectory_id;
  s.on_trajectory = msg.state == setpoint_t::STATE_TRACKING || msg.state == setpoint_t::STATE_END;
  s.state.position = toVec3(msg.position);
  s.state.velocity = toVec3(msg.velocity);
  s.state.acceleration = toVec3(msg.acceleration);
  s.jerk = toVec3(msg.jerk);
  s.yaw_rad = msg.yaw_rad;
  sim_.setSetpoint(s);
  ctx_.increment("setpoints_received");
}

odometry_t SimNode::makeOdometry() const {
  odometry_t msg{};
  msg.header.utime = sim_.nowUtime();
  const KinematicState& s = sim_.vehicle().state();
  fromVec3(s.position, msg.position);
  fromVec3(s.velocity, msg.velocity);
  fromVec3(s.acceleration, msg.acceleration);
  const Eigen::Quaterniond q = sim_.vehicle().orientation();
  msg.orientation[0] = q.w();
  msg.orientation[1] = q.x();
  msg.orientation[2] = q.y();
  msg.orientation[3] = q.z();
  return msg;
}

pointcloud_t SimNode::makePointcloud(const sim::Scan& scan) const {
  pointcloud_t msg{};
  msg.header.utime = sim_.nowUtime();
  msg.sensor_kind = scan.kind == sim::SensorKind::kDepth ? pointcloud_t::SENSOR_DEPTH
                                                         : pointcloud_t::SENSOR_LIDAR;
  fromVec3(scan.position, msg.sensor_position);
  msg.sensor_orientation[0] = scan.orientation.w();
  msg.sensor_orientation[1] = scan.orientation.x();
  msg.sensor_orientation[2] = scan.orientation.y();
  msg.sensor_orientation[3] = scan.orientation.z();
  msg.max_range_m = static_cast<float>(scan.max_range_m);
  msg.xyz = scan.xyz;
  msg.num_coords = static_cast<int32_t>(msg.xyz.size());
  return msg;
}

mission_status_t SimNode::makeMissionStatus() const {
  const sim::MissionMetrics& m = sim_.metrics();
  mission_status_t msg{};
  msg.header.utime = sim_.nowUtime();
  msg.active = !m.reached;
  msg.reached = m.reached;
  msg.collided = m.collided;
  msg.flight_time_s = m.flight_time_s;
  msg.distance_m = m.distance_m;
  msg.energy = m.energy;
  fromVec3(sim_.vehicle().state().position, msg.position);
  fromVec3(m.goal, msg.goal);
  // The message has no infinity: without obstacles report a large clearance.
  msg.min_clearance_m = std::isfinite(m.min_clearance_m) ? m.min_clearance_m : 1e6;
  msg.waypoint_index = m.waypoint_index;
  msg.num_waypoints = m.num_waypoints;
  msg.num_arrivals = static_cast<int32_t>(m.arrivals.size());
  for (const sim::WaypointArrival& a : m.arrivals) {
    msg.arrival_waypoint.push_back(a.waypoint_index);
    msg.arrival_time_s.push_back(a.flight_time_s);
    msg.arrival_speed_mps.push_back(a.speed_mps);
  }
  msg.follows_setpoints = m.follows_setpoints;
  msg.tracking_error_rms_m = m.tracking_error_rms_m;
  msg.tracking_error_max_m = m.tracking_error_max_m;
  return msg;
}

void SimNode::reportNew(const char* counter, int total, int* seen,
                        const std::function<std::string()>& what) {
  if (total == *seen) return;
  ctx_.increment(counter, total - *seen);
  *seen = total;
  logWarn(ctx_.service() + ": " + what());
}

void SimNode::step(bool publish_scans) {
  const sim::Simulator::StepResult r = sim_.step();
  ctx_.clock().observe(sim_.nowUtime());
  odometry_t odom = makeOdometry();
  ctx_.publish(channels::kOdometry, odom);
  if (r.scan && !publish_scans) ctx_.increment("scans_skipped_late");
  if (r.scan && publish_scans) {
    pointcloud_t cloud = makePointcloud(sim_.lastScan());
    ctx_.publish(channels::kPointcloud, cloud);
  }
  const sim::Vehicle& v = sim_.vehicle();
  // (Messages are built only when a counter grew: this runs every step.)
  auto id = [&] { return std::to_string(v.activeTrajectoryId()); };
  // The committed trajectory did not start where the vehicle was: a planner/arbiter bug.
  reportNew("trajectory_jumps", v.jumps(), &jumps_seen_, [&] {
    return "trajectory " + id() + " does not start where the vehicle is: jumped " +
           std::to_string(v.lastJump()) + " m";
  });
  reportNew("trajectories_lost", v.lostCommits(), &lost_commits_seen_, [&] {
    return std::to_string(v.lostCommits()) +
           " TRAJECTORY message(s) lost in transport so far (a gap in the trajectory ids; raise "
           "the receive buffers, docs/operations.md)";
  });
  reportNew("trajectory_jumps_after_loss", v.jumpsAfterLoss(), &jumps_after_loss_seen_, [&] {
    return "trajectory " + id() + " continues a lost one, not what the vehicle flew: stepped " +
           std::to_string(v.lastJump()) + " m";
  });
  reportNew("trajectories_late", v.lateTakeovers(), &late_takeovers_seen_, [&] {
    return "trajectory " + id() + " arrived " +
           std::to_string(static_cast<int>(v.lastLatenessS() * 1e3)) +
           " ms after its start time (delivered late: the commit's lead was shorter than the "
           "delay); taken over with a " +
           std::to_string(v.lastLateStepM()) + " m step";
  });
  const sim::MissionMetrics& m = sim_.metrics();
  if (m.reached && !reported_reached_) {
    reported_reached_ = true;
    std::ostringstream out;
    out << ctx_.service() << ": goal reached after " << m.flight_time_s << " s (bound "
        << m.time_bound_s << " s), " << m.distance_m << " m, energy " << m.energy
        << ", min clearance " << m.min_clearance_m << " m";
    logInfo(out.str());
  }
  if (!m.reached) reported_reached_ = false;
  if (m.arrivals.size() != arrivals_reported_) {
    for (; arrivals_reported_ < m.arrivals.size(); ++arrivals_reported_) {
      const sim::WaypointArrival& a = m.arrivals[arrivals_reported_];
      std::ostringstream out;
      out << ctx_.service() << ": waypoint " << a.waypoint_index + 1 << " of " << m.num_waypoints
          << " reached after " << a.flight_time_s << " s at " << a.speed_mps << " m/s";
      logInfo(out.str());
    }
  }
  if (m.collided && !reported_collision_) {
    reported_collision_ = true;
    ctx_.increment("collisions");
    std::ostringstream out;
    out << ctx_.service() << ": COLLISION at (" << m.collision_position.x() << ", "
        << m.collision_position.y() << ", " << m.collision_position.z() << ")";
    logWarn(out.str());
  }
  if (r.status) {
    mission_status_t status = makeMissionStatus();
    ctx_.publish(channels::kMissionStatus, status);
  }
}

}  // namespace mmh
