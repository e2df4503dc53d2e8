#pragma once
// How rbserver runs: the `lcm:`, `server:` and `limits:` sections of a config
// file (read by the config loader, config/server_sections.h), which rbserver
// then overrides from its command line. Plain data: nothing here knows LCM,
// clocks or the daemon; the daemon and the bridge read these values.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rbsim/physics/world_settings.h"

namespace rbsim {

// What the step clock does when the loop falls behind (daemon/step_clock.h
// has the whole story): take the late steps back to back (Burst), or give
// up the lost time and re-anchor the schedule (Reanchor).
enum class CatchUpPolicy { Burst, Reanchor };

// What a server accepts in a wrench (configurable in the `limits:` section).
struct WrenchLimits {
  double maxForce = 1e6;         // N, magnitude
  double maxTorque = 1e6;        // N·m, magnitude
  double maxLeverArm = 1e3;      // m, |point − centre of mass| (world) or |point| (body)
  double maxDuration = 86400.0;  // s of simulated time
  int64_t maxStepsAhead = 100000000;  // how far ahead apply_at_step may schedule
};

struct ServerSettings {
  // LCM. ttl=0 keeps every packet on this host; recv_buf_size lets the
  // server take bursts of commands without the kernel dropping them.
  std::string lcmUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152";
  std::string channelPrefix = "RBSIM_";
  double stateRate = 100.0;  // Hz of simulated time; 0 = every step
  double statusRate = 2.0;   // Hz of wall-clock time, 1..10
  double contactsRate = 10.0;  // Hz of simulated time for RBSIM_CONTACTS; 0 = not published

  double realTimeFactor = 1.0;           // simulated s per wall s; 0 = as fast as possible
  std::optional<double> duration;        // s of simulated time, then a clean exit
  CatchUpPolicy catchUp = CatchUpPolicy::Burst;
  int maxBurst = 20;                     // steps, Burst policy only
  bool startPaused = false;
  // At start, listen this long (s) on the channel prefix before publishing:
  // a server heard there makes this one refuse to start (two servers on one
  // prefix interleave their states), unless allowOtherInstances, which only
  // warns. 0: no check. Command line: --instance-check S, --allow-other-instances.
  double instanceCheckSeconds = 0.25;
  bool allowOtherInstances = false;
  // The last part of the wait for a step deadline is spent polling instead
  // of sleeping, for wake-ups on time: a timer wake-up on a virtual machine
  // is often 50-150 µs late. Costs CPU: spin × step rate (25% of a core at
  // 1 kHz); `server.spin_us: 0` turns it off.
  int64_t spinNanoseconds = 250000;
  std::string recordPath;                // empty: no recording
  // Where SAVE_CHECKPOINT, RESET with a path and --checkpoint-every put and
  // find checkpoint files; empty: checkpoints disabled.
  std::string checkpointDirectory;
  double checkpointEvery = 0.0;          // s of simulated time between periodic checkpoints; 0 = none
  // Where mesh files of bodies spawned over LCM must lie (`server:
  // spawn_mesh_directory`, relative to the config file); empty: the config
  // file's directory. Config files themselves may name meshes anywhere.
  std::string spawnMeshDirectory;

  WrenchLimits limits;
  // The numerical guard's speed limits, handed to the world (main.cpp): a
  // body faster than these is frozen and reported.
  StateLimits stateLimits;
  double maxRealTimeFactor = 1000.0;     // SET_REAL_TIME_FACTOR above this is rejected
  int64_t maxStepsPerCommand = 10000000; // STEP num_steps above this is rejected

  // Access control and limits of the command path (CommandHandler).
  bool readOnly = false;                 // every wrench and command is rejected; state still published
  // Bodies that accept external wrenches; unset: every body.
  std::optional<std::vector<std::string>> wrenchBodies;
  double clientRate = 5000.0;            // wrenches + commands per second per client id; 0 = unlimited
  double clientBurst = 5000.0;           // messages a client may send at once (token bucket size)
  int64_t maxMessageBytes = 262144;      // bytes; larger wrench/command messages are rejected undecoded
  int64_t maxBodies = 100000;            // SPAWN is rejected when the world would have more bodies
  int64_t maxJoints = 100000;            // ... or more joints than this
};

}  // namespace rbsim
