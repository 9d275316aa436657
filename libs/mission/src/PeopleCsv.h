#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "daep/perception/PeopleTracker.h"
#include "daep/world/People.h"

namespace daep::mission {

/** people.csv: the confirmed tracks after every depth frame (t,track,x,y,vx,vy,sigma). */
class PeopleCsv {
public:
    /** Creates the file; throws std::runtime_error naming it on failure. */
    explicit PeopleCsv(const std::string& path);

    void write(double t, const std::vector<perception::PersonForecast>& tracks);
    /** Throws std::runtime_error naming the file when a write failed. */
    void flush();

private:
    std::string path_;
    std::ofstream out_;
};

/**
 * people_truth.csv: where the simulated people really are after every depth frame
 * (t,person,x,y,vx,vy,heading), beside people.csv, so tracks and collisions can be judged
 * against the truth.
 */
class PeopleTruthCsv {
public:
    /** Creates the file; throws std::runtime_error naming it on failure. */
    explicit PeopleTruthCsv(const std::string& path);

    void write(double t, const std::vector<world::PersonState>& people);
    /** Throws std::runtime_error naming the file when a write failed. */
    void flush();

private:
    std::string path_;
    std::ofstream out_;
};

}  // namespace daep::mission
