// Messages between the performance page's peer section (peers.ts) and its worker
// (peers.worker.ts): one run of the peer benchmark's grid, its points as they are measured.
import type { PeerGrid, PeerPoint, PeerSettings } from '../../../bench/peers/comparison.mjs';

export type PeersCommand =
  | { type: 'run'; urls: { gaitlab: string; joltMT: string; joltST: string }; grid: PeerGrid; settings: PeerSettings }
  | { type: 'cancel' };

export type PeersEvent =
  | { type: 'status'; message: string }
  /** Every engine's result at the grid's point `index` (peerGrid's order). */
  | { type: 'points'; index: number; points: PeerPoint[]; seconds: number }
  | { type: 'done'; cancelled: boolean }
  | { type: 'error'; message: string };
