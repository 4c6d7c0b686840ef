// Ladders whose rungs depend on a parameter (issue 23). delta-tracking's rungs are
// fractions of the reader's spp, raymarch-steps' cost grows with the reader's N: a new
// value needs a new Ladder (refinement.ts), but the cost per unit of work measured on
// the old one still holds (it is the device's speed, not the parameter's). A family
// keeps one Ladder per key and seeds each new one with the cost per unit of work
// learnt so far, so a drag that visits a new value every input still starts each
// picture on the rung that fits the first-picture budget, instead of on the lowest.
import { Ladder, REFINE_STAGE_MS, type Rung, type RungChoice } from './refinement.ts';

/** How many ladders a family keeps (a drag over a slider's range visits about 20). */
const FAMILY_SIZE = 32;

export class LadderFamily<T> {
  /** Milliseconds per unit of work (rungs' work must be in the same unit for every key). */
  private msPerWork: number | null = null;
  private readonly ladders = new Map<string, Ladder<T>>();

  constructor(
    private readonly firstBudgetMs: number,
    private readonly stageBudgetMs = REFINE_STAGE_MS,
  ) {}

  /** The ladder of `key`, made from `rungs()` the first time and seeded with the known cost. */
  get(key: string, rungs: () => readonly Rung<T>[]): Ladder<T> {
    let ladder = this.ladders.get(key);
    if (ladder) {
      // Most recently used last, so the oldest is the first to go.
      this.ladders.delete(key);
      this.ladders.set(key, ladder);
      return ladder;
    }
    ladder = new Ladder(rungs(), this.firstBudgetMs, this.stageBudgetMs);
    if (this.msPerWork !== null) {
      const first = ladder.rungs[0]!;
      ladder.record(0, this.msPerWork * first.work);
    }
    this.ladders.set(key, ladder);
    for (const old of this.ladders.keys()) {
      if (this.ladders.size <= FAMILY_SIZE) break;
      this.ladders.delete(old);
    }
    return ladder;
  }

  /** Learns a frame's cost on `ladder` (the ladder's own estimate and the family's). */
  record(ladder: Ladder<T>, choice: RungChoice<T>, milliseconds: number): void {
    const work = choice.rung.work;
    if (!(milliseconds >= 0) || !(work > 0)) return;
    ladder.record(choice.index, milliseconds);
    const perWork = milliseconds / work;
    // Smoothed as Ladder.record smooths (α = ½).
    this.msPerWork = this.msPerWork === null ? perWork : 0.5 * (this.msPerWork + perWork);
  }
}
