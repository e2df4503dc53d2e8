#pragma once
// Keeping a file named by an untrusted party inside one directory.
//
// A config file given on the command line is trusted: its mesh paths may go
// anywhere. A body spawned over LCM is not: anyone on the multicast group can
// send one, and its mesh file is opened on the server host. So the mesh of a
// spawned body, a spawned robot's URDF and every mesh that URDF names must
// be a regular file under the spawn mesh directory:
//  - a relative path (no leading '/'),
//  - with no '..' component (even one that would stay inside: the rule is
//    simpler to state and to check than "stays inside lexically"),
//  - whose canonical path, with every symbolic link resolved, is still under
//    the canonical directory (a link inside that points out is refused),
//  - and that is a regular file (not a FIFO or a device, which could block
//    the server's only thread or feed it without end).
// The canonical path is returned and is what gets opened, so a link cannot
// be swapped in between the check and the open by anyone who cannot write
// to the directory itself.

#include <string>

#include "rbsim/physics/types.h"

namespace rbsim {

// `file` as given in the message; `directory` the spawn mesh directory (""
// is the current directory). Errors say which rule `file` broke.
Expected<std::string> resolveContainedFile(const std::string& file, const std::string& directory);

}  // namespace rbsim
