// SPDX-License-Identifier: MIT
// Debian's Chromium, headless, driven by playwright-core: nothing downloads a
// browser. The flags keep it off the network and work as root.
import {chromium} from 'playwright-core';

export const kChromium = process.env.CALDER_CHROMIUM || '/usr/bin/chromium';

export async function launch() {
  return chromium.launch({
    executablePath: kChromium,
    headless: true,
    args: [
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
      '--disable-background-timer-throttling',
      '--disable-renderer-backgrounding',
    ],
  });
}
