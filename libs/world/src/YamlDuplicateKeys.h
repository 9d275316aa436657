#pragma once

#include <optional>
#include <string>

namespace daep::world {

/** A key given twice in one YAML mapping; lines are 1-based. */
struct DuplicateKey {
    std::string key;
    int line = 0;
    int firstLine = 0;
};

/**
 * The first key that appears twice in the same mapping of a YAML document, block or flow style
 * ({a: 1, a: 2}). MRPT's parser keeps one of the two silently, so a world file that says
 * `ground: true` twice, or a box with two `center:` keys, would load with one value dropped.
 * Covers the YAML the world files use: block mappings and lists, flow collections (also over
 * several lines), quoted scalars, comments and block scalars (| and >).
 */
std::optional<DuplicateKey> findDuplicateKey(const std::string& text);

}  // namespace daep::world
