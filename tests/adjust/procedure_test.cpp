// The adjustment procedure without a window: plan, question order, grid clamping, going back,
// auto-repeat, pausing, resuming and practice trials.

#include "adjust/procedure.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace countershade::adjust {
namespace {

std::vector<Condition> conditions(int n, int grid = 11) {
  std::vector<Condition> out;
  for (int i = 0; i < n; ++i)
    out.push_back({"scene" + std::to_string(i % 3), "usm3d", 0.01 * (1 + i / 3), grid});
  return out;
}

PlanSettings settings(uint64_t seed, int repetitions = 1, Side side = Side::counterbalanced,
                      StartMode start = StartMode::random) {
  PlanSettings s;
  s.seed = seed;
  s.repetitions = repetitions;
  s.side = side;
  s.start = start;
  return s;
}

bool same_plan(const std::vector<Trial>& a, const std::vector<Trial>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].condition != b[i].condition || a[i].repetition != b[i].repetition ||
        a[i].side != b[i].side || a[i].start_index[0] != b[i].start_index[0] ||
        a[i].start_index[1] != b[i].start_index[1] || a[i].start_index[2] != b[i].start_index[2])
      return false;
  return true;
}

TEST(AdjustPlan, EveryConditionAndRepetitionExactlyOnceNumberedInOrder) {
  auto c = conditions(7);
  auto plan = plan_trials(c, settings(3, 3));
  ASSERT_EQ(plan.size(), 21u);
  std::set<std::pair<int, int>> seen;
  for (size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(plan[i].number, int(i) + 1);
    EXPECT_FALSE(plan[i].practice);
    EXPECT_TRUE(seen.insert({plan[i].condition, plan[i].repetition}).second);
  }
}

TEST(AdjustPlan, ReproducibleFromTheSeedAndDifferentForAnotherSeed) {
  auto c = conditions(12);
  EXPECT_TRUE(same_plan(plan_trials(c, settings(42, 2)), plan_trials(c, settings(42, 2))));
  EXPECT_FALSE(same_plan(plan_trials(c, settings(42, 2)), plan_trials(c, settings(43, 2))));
  // The order really is shuffled: not the condition order.
  auto plan = plan_trials(c, settings(42, 1));
  int in_place = 0;
  for (size_t i = 0; i < plan.size(); ++i) in_place += plan[i].condition == int(i);
  EXPECT_LT(in_place, 6);
}

TEST(AdjustPlan, CounterbalancingAlternatesSidesOverRepetitionsAndBalancesConditions) {
  auto c = conditions(9);
  auto plan = plan_trials(c, settings(5, 2));
  std::map<int, std::set<Side>> sides;
  for (const auto& t : plan) sides[t.condition].insert(t.side);
  for (const auto& [condition, s] : sides) EXPECT_EQ(s.size(), 2u) << "condition " << condition;

  for (uint64_t seed = 1; seed <= 20; ++seed) {
    auto one = plan_trials(c, settings(seed, 1));
    int left = 0;
    for (const auto& t : one) left += t.side == Side::left;
    EXPECT_TRUE(left == 4 || left == 5) << "seed " << seed << ": " << left << " of 9 on the left";
  }
  for (Side fixed : {Side::left, Side::right})
    for (const auto& t : plan_trials(c, settings(5, 2, fixed))) EXPECT_EQ(t.side, fixed);
}

TEST(AdjustPlan, StartIndicesAreSeededAndCoverTheGridOrAreZero) {
  auto c = conditions(6, 21);
  auto plan = plan_trials(c, settings(9, 4));
  std::set<int> starts;
  for (const auto& t : plan)
    for (int q = 0; q < kQuestionCount; ++q) {
      EXPECT_GE(t.start_index[q], 0);
      EXPECT_LT(t.start_index[q], 21);
      starts.insert(t.start_index[q]);
    }
  EXPECT_GT(starts.size(), 12u);  // 72 draws from 21 values
  EXPECT_TRUE(starts.count(0) || starts.count(1));
  for (const auto& t : plan_trials(c, settings(9, 4, Side::counterbalanced, StartMode::zero)))
    for (int q = 0; q < kQuestionCount; ++q) EXPECT_EQ(t.start_index[q], 0);
}

TEST(AdjustPlan, PracticeTrialsComeFirstAndDoNotChangeTheRealOrder) {
  auto c = conditions(5);
  PlanSettings s = settings(11, 2);
  auto without = plan_trials(c, s);
  s.practice_trials = 2;
  auto with = plan_trials(c, s);
  ASSERT_EQ(with.size(), without.size() + 2);
  EXPECT_TRUE(with[0].practice && with[1].practice);
  EXPECT_EQ(with[0].number, 0);
  EXPECT_TRUE(same_plan(std::vector<Trial>(with.begin() + 2, with.end()), without));
}

TEST(AdjustProcedure, QuestionsComeInOrderLowHighBestThenTheNextTrial) {
  auto c = conditions(2);
  auto plan = plan_trials(c, settings(1, 1, Side::left, StartMode::zero));
  Procedure p(c, plan);
  EXPECT_EQ(p.phase(), Procedure::Phase::instructions);
  EXPECT_FALSE(p.press(Key::right, 0.0));  // arrows do nothing on the instruction screen
  p.press(Key::enter, 1.0);
  std::vector<std::pair<int, Question>> order;
  double t = 2;
  while (!p.done()) {
    ASSERT_EQ(p.phase(), Procedure::Phase::question);
    auto a = p.press(Key::enter, t += 1);
    ASSERT_TRUE(a);
    order.push_back({a->trial_index, a->question});
  }
  EXPECT_EQ(p.phase(), Procedure::Phase::finished);
  const std::vector<std::pair<int, Question>> expected = {{0, Question::low},  {0, Question::high},
                                                          {0, Question::best}, {1, Question::low},
                                                          {1, Question::high}, {1, Question::best}};
  EXPECT_EQ(order, expected);
  EXPECT_EQ(p.answered_count(), 6);
}

TEST(AdjustProcedure, ArrowsStepTheGridIndexAndClampAtBothEnds) {
  auto c = conditions(1, 5);
  auto plan = plan_trials(c, settings(1, 1, Side::left, StartMode::zero));
  Procedure p(c, plan);
  p.press(Key::enter, 0);
  for (int i = 0; i < 3; ++i) p.press(Key::down, 1 + i), p.release(Key::down, 1 + i);
  EXPECT_EQ(p.lambda_index(), 0);
  for (int i = 0; i < 9; ++i) {
    p.press(i % 2 ? Key::up : Key::right, 10 + i);
    p.release(i % 2 ? Key::up : Key::right, 10 + i);
  }
  EXPECT_EQ(p.lambda_index(), 4);
  p.press(Key::left, 30), p.release(Key::left, 30);
  EXPECT_EQ(p.lambda_index(), 3);
  auto a = p.press(Key::enter, 31);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->lambda_index, 3);
  EXPECT_EQ(a->start_index, 0);
  EXPECT_EQ(a->n_keypresses, 13);
  EXPECT_DOUBLE_EQ(a->rt_s, 31.0);
}

TEST(AdjustProcedure, BackspaceReturnsToThePreviousQuestionWithItsAnswerAndRaisesTheRevision) {
  auto c = conditions(2, 9);
  auto plan = plan_trials(c, settings(1, 1, Side::left, StartMode::zero));
  Procedure p(c, plan);
  p.press(Key::enter, 0);
  p.press(Key::backspace, 0.5);  // nothing before the first question
  EXPECT_EQ(p.question(), Question::low);
  for (int i = 0; i < 3; ++i) p.press(Key::right, 1), p.release(Key::right, 1);
  auto low = p.press(Key::enter, 2);
  ASSERT_TRUE(low);
  EXPECT_EQ(low->revision, 0);
  EXPECT_EQ(p.question(), Question::high);
  p.press(Key::right, 3), p.release(Key::right, 3);
  p.press(Key::backspace, 4);
  EXPECT_EQ(p.question(), Question::low);
  EXPECT_EQ(p.lambda_index(), 3);  // the answer given, not the start
  p.press(Key::right, 5), p.release(Key::right, 5);
  auto again = p.press(Key::enter, 6);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->question, Question::low);
  EXPECT_EQ(again->lambda_index, 4);
  EXPECT_EQ(again->revision, 1);
  EXPECT_EQ(p.question(), Question::high);
  EXPECT_EQ(p.lambda_index(), 0);  // high was never answered: back to its start index
  EXPECT_EQ(p.answered_count(), 1);
  // Backspace never crosses into the previous trial.
  p.press(Key::enter, 7);
  p.press(Key::enter, 8);
  EXPECT_EQ(p.trial_index(), 1);
  p.press(Key::backspace, 9);
  EXPECT_EQ(p.trial_index(), 1);
  EXPECT_EQ(p.question(), Question::low);
}

TEST(AdjustProcedure, HeldKeysRepeatAtTheConfiguredRateOnly) {
  auto c = conditions(1, 30);
  auto plan = plan_trials(c, settings(1, 1, Side::left, StartMode::zero));
  RepeatTiming timing;
  timing.repeat_delay_s = 0.4;
  timing.repeat_interval_s = 0.1;
  Procedure p(c, plan, timing);
  p.press(Key::enter, 0);
  p.press(Key::right, 1.0);
  EXPECT_EQ(p.lambda_index(), 1);
  p.tick(1.39);
  EXPECT_EQ(p.lambda_index(), 1);
  p.tick(1.40);
  EXPECT_EQ(p.lambda_index(), 2);
  p.tick(1.7001);  // repeats at 1.5, 1.6 and 1.7
  EXPECT_EQ(p.lambda_index(), 5);
  p.release(Key::right, 1.75);
  p.tick(3.0);
  EXPECT_EQ(p.lambda_index(), 5);
  // Repeats due before a release count even when no tick came in between (a late frame).
  p.press(Key::right, 2.0);
  p.release(Key::right, 2.75);  // steps at 2.0, then 2.4, 2.5, 2.6, 2.7
  EXPECT_EQ(p.lambda_index(), 10);
  // Holding down repeats downwards and stops at 0.
  p.press(Key::down, 4.0);
  p.tick(10.0);
  EXPECT_EQ(p.lambda_index(), 0);
  p.release(Key::down, 10.0);
  auto a = p.press(Key::enter, 11.0);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->n_keypresses, 3);  // presses, not repeats
}

TEST(AdjustProcedure, PauseFreezesTheTrialAndQuitEndsTheSession) {
  auto c = conditions(2, 9);
  auto plan = plan_trials(c, settings(1, 1, Side::left, StartMode::zero));
  Procedure p(c, plan);
  p.press(Key::enter, 0);
  p.press(Key::right, 1), p.release(Key::right, 1);
  p.press(Key::escape, 2);
  EXPECT_EQ(p.phase(), Procedure::Phase::paused);
  EXPECT_FALSE(p.press(Key::right, 3));
  EXPECT_EQ(p.phase(), Procedure::Phase::paused);
  p.press(Key::enter, 12);  // resume after 10 s
  EXPECT_EQ(p.phase(), Procedure::Phase::question);
  EXPECT_EQ(p.lambda_index(), 1);
  auto a = p.press(Key::enter, 13);
  ASSERT_TRUE(a);
  EXPECT_DOUBLE_EQ(a->rt_s, 3.0);  // 13 s minus the 10 s pause
  p.press(Key::escape, 14);
  p.press(Key::quit, 15);
  EXPECT_EQ(p.phase(), Procedure::Phase::quit);
  EXPECT_TRUE(p.done());
  EXPECT_FALSE(p.press(Key::enter, 16));
}

TEST(AdjustProcedure, ResumeStartsAtTheFirstUnansweredQuestionAndSkipsPractice) {
  auto c = conditions(3, 9);
  PlanSettings s = settings(2, 1);
  s.practice_trials = 1;
  auto plan = plan_trials(c, s);
  Procedure p(c, plan);
  // Plan index 0 is practice; 1 is answered completely; 2 has its low answer.
  p.resume({{{1, 0}, {2, 0}}, {{1, 1}, {5, 0}}, {{1, 2}, {3, 1}}, {{2, 0}, {4, 0}}});
  EXPECT_EQ(p.phase(), Procedure::Phase::instructions);
  p.press(Key::enter, 0);
  EXPECT_EQ(p.trial_index(), 2);
  EXPECT_EQ(p.question(), Question::high);
  EXPECT_EQ(p.lambda_index(), plan[2].start_index[1]);
  p.press(Key::backspace, 1);
  EXPECT_EQ(p.lambda_index(), 4);  // the recorded answer
  auto a = p.press(Key::enter, 2);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->revision, 1);

  Procedure complete(c, plan);
  std::map<std::pair<int, int>, PastAnswer> all;
  for (int t = 1; t < 4; ++t)
    for (int q = 0; q < 3; ++q) all[{t, q}] = {0, 0};
  complete.resume(all);
  EXPECT_EQ(complete.phase(), Procedure::Phase::finished);
}

TEST(AdjustProcedure, PracticeTrialsEndWithAnAnnouncementAndDoNotCount) {
  auto c = conditions(2, 5);
  PlanSettings s = settings(2, 1, Side::right, StartMode::zero);
  s.practice_trials = 1;
  Procedure p(c, plan_trials(c, s));
  p.press(Key::enter, 0);
  EXPECT_TRUE(p.trial().practice);
  for (int q = 0; q < 3; ++q) ASSERT_TRUE(p.press(Key::enter, 1 + q));
  EXPECT_EQ(p.phase(), Procedure::Phase::practice_done);
  EXPECT_EQ(p.answered_count(), 0);
  p.press(Key::enter, 5);
  EXPECT_FALSE(p.trial().practice);
  EXPECT_EQ(p.trial().number, 1);
  EXPECT_EQ(p.real_trial_count(), 2);
}

}  // namespace
}  // namespace countershade::adjust
