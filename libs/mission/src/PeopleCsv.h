#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "daep/perception/PeopleTracker.h"
#include "daep/world/People.h"

namespace daep::mission {

/** One CSV output file: created with its header, written row by row, checked at flush. */
class CsvFile {
public:
    /** Creates the file with its header line; throws std::runtime_error naming it on failure. */
    CsvFile(const std::string& path, const char* header);

    std::ostream& out() { return out_; }
    /** Throws std::runtime_error naming the file when a write failed. */
    void flush();

private:
    std::string path_;
    std::ofstream out_;
};

/** people.csv: the confirmed tracks after every depth frame (t,track,x,y,vx,vy,sigma). */
class PeopleCsv {
public:
    explicit PeopleCsv(const std::string& path) : file_(path, "t,track,x,y,vx,vy,sigma") {}

    void write(double t, const std::vector<perception::PersonForecast>& tracks);
    void flush() { file_.flush(); }

private:
    CsvFile file_;
};

/**
 * people_truth.csv: where the simulated people really are after every depth frame
 * (t,person,x,y,vx,vy,heading), beside people.csv, so tracks and collisions can be judged
 * against the truth.
 */
class PeopleTruthCsv {
public:
    explicit PeopleTruthCsv(const std::string& path) : file_(path, "t,person,x,y,vx,vy,heading") {}

    void write(double t, const std::vector<world::PersonState>& people);
    void flush() { file_.flush(); }

private:
    CsvFile file_;
};

}  // namespace daep::mission
