#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace daep::mission {

class ExperimentConfig;

struct DetectionEvalOptions {
    /** People and detections farther than this from the sensor (horizontally, m) are not scored. */
    double range = 5.0;
    /**
     * A person is unoccluded when at least this share of the pixels whose rays meet its body
     * box (on an image extended past its borders) return the box itself: occlusion by static
     * geometry or other people and truncation by the field of view both lower it.
     */
    double minVisibleFraction = 0.5;
    /** A detection within this distance (m) of a true body centre is that person. */
    double matchDistance = 0.75;
};

struct DetectionScore {
    std::size_t frames = 0;
    std::size_t eligible = 0;               ///< unoccluded people within range, summed over frames
    std::size_t found = 0;                  ///< of those, matched by a detection
    std::size_t detections = 0;             ///< detections within range
    std::size_t truePositives = 0;          ///< of those, matched to a person (occluded or not)
    std::size_t falsePositives = 0;         ///< of those, matched to nobody
    std::vector<double> errors;             ///< m, detected - true centre of every found person
    std::size_t confirmedTracks = 0;        ///< confirmed tracks within range, over frames
    std::size_t confirmedTrackMatches = 0;  ///< of those, within matchDistance of a person
    std::size_t occludedOrTruncated = 0;    ///< people within range that were not eligible

    double recall() const { return eligible ? double(found) / double(eligible) : 0.0; }
    double precision() const {
        return detections ? double(truePositives) / double(detections) : 0.0;
    }
    double trackPrecision() const {
        return confirmedTracks ? double(confirmedTrackMatches) / double(confirmedTracks) : 0.0;
    }
};

/**
 * Replays a rawlog recorded by a simulated run (output.rawlog = true: depth frames, DRONE_POSE
 * and every PERSON_<i>) through the map, the PeopleDetector and the PeopleTracker with the
 * experiment's [map], [detector], [tracker], [people] and [rawlog] settings, and scores the
 * detections of each frame against the true people. Writes one CSV row per frame to
 * `frameCsv` when given: t, eligible, found, detections, false_positives, confirmed_tracks.
 * Throws InputError when the rawlog has no depth frames or no PERSON_<i> poses.
 */
DetectionScore evaluateDetection(const ExperimentConfig& config, const std::string& rawlogPath,
                                 const DetectionEvalOptions& options,
                                 std::ostream* frameCsv = nullptr);

}  // namespace daep::mission
