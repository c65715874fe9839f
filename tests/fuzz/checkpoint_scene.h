// The scene of the checkpoint fuzzer and of its seeds (make_seeds.cpp): a solid and a fluid, so
// both kinds of model state are in the file. A checkpoint is tied to its scene's hash.
#pragma once

namespace talus::fuzz {

inline const char* kCheckpointScene = R"(
[simulation]
dx = 0.2
end_time = 1
[domain]
min = [0, 0, 0]
max = [1, 1, 1]
[[materials]]
name = "rock"
preset = "rock"
[[materials]]
name = "water"
preset = "water"
[[bodies]]
material = "rock"
shape = "box"
min = [0.2, 0.2, 0.2]
max = [0.4, 0.4, 0.4]
[[bodies]]
material = "water"
shape = "box"
min = [0.6, 0.6, 0.2]
max = [0.8, 0.8, 0.4]
)";

} // namespace talus::fuzz
