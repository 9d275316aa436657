#include "daep/perception/PeopleTracker.h"

#include <algorithm>
#include <stdexcept>

namespace daep::perception {

PeopleTracker::PeopleTracker(const TrackerParams& params) : params_(params) {
    if (params.dropAfter <= 0)
        throw std::invalid_argument("PeopleTracker: dropAfter must be positive");
}

PeopleTracker::Track* PeopleTracker::findById(int id) {
    for (Track& t : tracks_)
        if (t.id == id)
            return &t;
    return nullptr;
}

void PeopleTracker::updateOrStart(double time, int id, const PersonMeasurement& m) {
    if (Track* t = findById(id)) {
        t->filter.update(time, m.position, m.covariance);
        t->lastSeen = time;
        return;
    }
    tracks_.push_back({id, PersonTrack(params_.predictor, time, m.position), time});
}

void PeopleTracker::update(double time, const std::vector<PersonMeasurement>& measurements) {
    for (const PersonMeasurement& m : measurements)
        updateOrStart(time, m.id >= 0 ? m.id : nextAnonymousId_++, m);
    dropStale(time);
}

void PeopleTracker::dropStale(double time) {
    tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                                 [&](const Track& t) {
                                     return time - t.lastSeen > params_.dropAfter;
                                 }),
                  tracks_.end());
}

std::vector<PersonForecast> PeopleTracker::forecasts() const {
    std::vector<PersonForecast> out;
    out.reserve(tracks_.size());
    for (const Track& t : tracks_)
        out.push_back(t.filter.forecast(t.id));
    return out;
}

}  // namespace daep::perception
