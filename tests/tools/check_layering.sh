#!/bin/sh
# The server's libraries depend one way (server/CMakeLists.txt lists them,
# lowest first): checks that no source of a library includes a header of a
# library above it, and that LCM and yaml-cpp appear only where they belong.
# Prints every violation as FILE:LINE: the include, and fails if any.
#   tests/tools/check_layering.sh SERVER_DIR
set -u
server=$1
status=0

# forbid DIR PATTERN WHY: no line of server/DIR/* may match PATTERN.
forbid() {
  hits=$(grep -rnE "$2" "$server/$1" --include='*.h' --include='*.cpp') || true
  if [ -n "$hits" ]; then
    echo "$hits" | sed "s|^$server/|server/|; s|\$|   <- $1/ $3|"
    status=1
  fi
}

above_config='#include "(session|persist|bridge|replay|daemon)/'
forbid physics '#include "(config|session|persist|bridge|replay|daemon)/' "is below every other library"
forbid physics '#include <(lcm/|rbsim/|yaml-cpp/)' "has no LCM and no config files"
forbid meshio '#include "(robot|config|session|persist|bridge|replay|daemon)/' "depends on physics only"
forbid robot '#include "(config|session|persist|bridge|replay|daemon)/' "depends on physics and meshio only"
forbid robot '#include <(lcm/|rbsim/|yaml-cpp/)' "knows no LCM and no config files"
forbid sensors '#include "(meshio|robot|config|session|persist|bridge|replay|daemon)/' "depends on physics only"
forbid sensors '#include <(lcm/|rbsim/|yaml-cpp/)' "has no LCM and no config files"
forbid config "$above_config" "depends on physics, meshio, robot and sensors only"
forbid config '#include <(lcm/|rbsim/)' "knows no LCM"
forbid session '#include "(config|persist|bridge|replay|daemon)/' "depends on physics only"
forbid session '#include <(lcm/|rbsim/|yaml-cpp/)' "has no LCM and no config files"
forbid persist '#include "(config|bridge|replay|daemon)/' "depends on session and physics only"
forbid persist '#include <(lcm/|rbsim/|yaml-cpp/)' "has no LCM and no config files"
forbid bridge '#include "(replay|daemon)/' "is below replay and daemon"
forbid bridge '#include <(lcm/lcm|yaml-cpp/)' "has no LCM handle and does not read YAML itself"
forbid replay '#include "daemon/' "is below daemon"
forbid replay '#include <yaml-cpp/' "does not read YAML"
# Outside the physics library, physics is used through its public headers.
for library in meshio robot sensors config session persist bridge replay daemon; do
  forbid $library '#include "physics/' "uses physics through its public headers (rbsim/physics/) only"
done
# The config file is read once, by config/: nothing else parses YAML.
forbid daemon '#include <yaml-cpp/' "gets its settings from config/ (the file is parsed once)"
exit $status
